//! Embeds an rpath to the SCIP shared library directory (the `NETSPEC_SCIP_LIBDIR` that
//! `scripts/setup.sh` writes into `.cargo/config.toml`), so the extension module loads SCIP
//! without `LD_LIBRARY_PATH`, as the `netspec` binary does.
fn main() {
    println!("cargo:rerun-if-env-changed=NETSPEC_SCIP_LIBDIR");
    if let Ok(dir) = std::env::var("NETSPEC_SCIP_LIBDIR") {
        println!("cargo:rustc-link-arg=-Wl,-rpath,{dir}");
    }
}
