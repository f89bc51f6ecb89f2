//! Embeds an rpath to the SCIP shared library directory (from the `links = "scip"` override
//! written by `scripts/setup.sh`), so the binaries and tests run without `LD_LIBRARY_PATH`.
fn main() {
    println!("cargo:rerun-if-env-changed=DEP_SCIP_LIBDIR");
    if let Ok(dir) = std::env::var("DEP_SCIP_LIBDIR") {
        println!("cargo:rustc-link-arg=-Wl,-rpath,{dir}");
    }
}
