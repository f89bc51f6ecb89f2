//! One path from settings to solve options: the command line's flags, a spec's `[solver]`
//! section and a city spec's are each a [`Settings`] layer with its [`Origin`]; every layer is
//! checked on its own (errors name the flag, or the file and field), then the layers are merged,
//! the first one given winning.

use super::search::Method;
use crate::solvers::{InvalidOption, LogTarget, RawParam, SolveOptions, SolverKind};
use crate::spec::SolverSpec;
use std::path::PathBuf;

/// Where a layer of settings came from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Origin {
    /// Command-line flags (`--gap`).
    Flags,
    /// A spec's `[solver]` section (`FILE: solver.gap`).
    Spec(PathBuf),
    /// A city spec's `[solver]` section (`FILE: solver.gap`).
    City(PathBuf),
}

impl Origin {
    /// How an error names the option `field` of [`SolveOptions`] from this origin.
    fn place(&self, field: &str) -> String {
        match self {
            Origin::Flags => match field {
                "time_limit" => "--time-limit",
                "rel_gap" => "--gap",
                "abs_gap" => "--abs-gap",
                "threads" => "--threads",
                "seed" => "--seed",
                "node_limit" => "--node-limit",
                "log" => "--log-file",
                other => other,
            }
            .to_string(),
            Origin::Spec(path) | Origin::City(path) => {
                let key = match field {
                    "rel_gap" => "gap",
                    other => other,
                };
                format!("{}: solver.{key}", path.display())
            }
        }
    }
}

pub use crate::spec::SettingsError;

/// Solve settings from one origin, each optional.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Settings {
    /// A MILP backend or a search.
    pub method: Option<Method>,
    /// Wall-clock limit in seconds (infinite: none).
    pub time_limit: Option<f64>,
    /// Relative gap.
    pub gap: Option<f64>,
    /// Absolute gap.
    pub abs_gap: Option<f64>,
    /// Threads.
    pub threads: Option<u32>,
    /// Seed.
    pub seed: Option<u64>,
    /// Node limit.
    pub node_limit: Option<u64>,
    /// The solver's own log.
    pub log: Option<LogTarget>,
    /// Solver parameters passed through.
    pub params: Vec<RawParam>,
}

impl Settings {
    /// The settings of a spec's `[solver]` section.
    pub fn of_spec(s: &SolverSpec) -> Settings {
        Settings {
            method: s.name.map(Method::Milp),
            time_limit: s.time_limit,
            gap: s.gap,
            abs_gap: s.abs_gap,
            threads: s.threads,
            seed: s.seed,
            node_limit: s.node_limit,
            log: None,
            params: Vec::new(),
        }
    }

    /// These settings over `base`: each field of `self` where set, else `base`'s; parameters
    /// from both (`self`'s last, so a backend that applies them in order lets them win).
    pub fn over(&self, base: &Settings) -> Settings {
        Settings {
            method: self.method.or(base.method),
            time_limit: self.time_limit.or(base.time_limit),
            gap: self.gap.or(base.gap),
            abs_gap: self.abs_gap.or(base.abs_gap),
            threads: self.threads.or(base.threads),
            seed: self.seed.or(base.seed),
            node_limit: self.node_limit.or(base.node_limit),
            log: self.log.clone().or_else(|| base.log.clone()),
            params: base.params.iter().chain(&self.params).cloned().collect(),
        }
    }

    /// The solve options these settings give (not yet checked).
    fn options(&self) -> SolveOptions {
        SolveOptions {
            time_limit: self.time_limit,
            rel_gap: self.gap,
            abs_gap: self.abs_gap,
            threads: self.threads,
            seed: self.seed,
            node_limit: self.node_limit,
            log: self.log.clone().unwrap_or(LogTarget::Quiet),
            params: self.params.clone(),
            ..SolveOptions::default()
        }
    }

    /// Checks every value, naming it as `origin` gives it: the options' ranges, and that a log
    /// file's folder exists (the same answer for every backend, before any runs).
    pub fn check(&self, origin: &Origin) -> Result<(), SettingsError> {
        self.options()
            .validate()
            .map_err(|e: InvalidOption| SettingsError { place: origin.place(e.option), reason: e.reason })?;
        if let Some(LogTarget::File(path)) = &self.log {
            let folder = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(std::path::Path::new("."));
            if !folder.is_dir() {
                return Err(SettingsError {
                    place: origin.place("log"),
                    reason: format!("{}: the folder {} does not exist", path.display(), folder.display()),
                });
            }
        }
        Ok(())
    }

    /// The fields this layer sets, as [`SolveOptions`] names them.
    fn set_fields(&self) -> Vec<&'static str> {
        let mut out = Vec::new();
        for (name, set) in [
            ("time_limit", self.time_limit.is_some()),
            ("rel_gap", self.gap.is_some()),
            ("abs_gap", self.abs_gap.is_some()),
            ("threads", self.threads.is_some()),
            ("seed", self.seed.is_some()),
            ("node_limit", self.node_limit.is_some()),
            ("log", self.log.is_some()),
        ] {
            if set {
                out.push(name);
            }
        }
        out
    }
}

/// Where an option of the resolved settings came from: `option` named as the layer that set it
/// gives it (`--seed`, `fig.toml: solver.seed`), for messages about it; `None` when no layer set it.
pub fn provenance(layers: &[(Origin, Settings)], option: &str) -> Option<String> {
    layers.iter().find(|(_, l)| l.set_fields().contains(&option)).map(|(o, _)| o.place(option))
}

/// Resolves layers given most important first (flags, then a spec's `[solver]`…) into the
/// method and the solve options: each layer is checked with its own names, then merged. The
/// method defaults to the embedded backend.
pub fn resolve(layers: &[(Origin, Settings)]) -> Result<(Method, SolveOptions), SettingsError> {
    let mut merged = Settings::default();
    for (origin, layer) in layers.iter().rev() {
        layer.check(origin)?;
        merged = layer.over(&merged);
    }
    let method = match merged.method {
        Some(m) => m,
        None => Method::Milp(SolverKind::default_kind().ok_or_else(|| SettingsError {
            place: "--solver".into(),
            reason: "has no default: no backend is compiled in".into(),
        })?),
    };
    Ok((method, merged.options()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Flags win over the spec, each layer's errors name its own source, and parameters of
    /// both layers reach the options.
    #[test]
    fn layers_merge_and_errors_name_their_source() {
        let spec = SolverSpec { gap: Some(0.1), threads: Some(2), seed: Some(7), ..Default::default() };
        let flags = Settings { gap: Some(0.01), time_limit: Some(5.0), ..Default::default() };
        let file = Origin::Spec("fig.toml".into());
        let (_, o) = resolve(&[(Origin::Flags, flags.clone()), (file.clone(), Settings::of_spec(&spec))]).unwrap();
        assert_eq!((o.rel_gap, o.threads, o.seed, o.time_limit), (Some(0.01), Some(2), Some(7), Some(5.0)));

        let bad_spec = SolverSpec { gap: Some(-1.0), ..Default::default() };
        let e = resolve(&[(Origin::Flags, flags.clone()), (file.clone(), Settings::of_spec(&bad_spec))]).unwrap_err();
        assert_eq!(e.place, "fig.toml: solver.gap");
        assert!(e.reason.contains("≥ 0"), "{e}");
        let bad_flag = Settings { threads: Some(0), ..Default::default() };
        let e = resolve(&[(Origin::Flags, bad_flag)]).unwrap_err();
        assert_eq!(e.to_string(), "--threads must be ≥ 1, got 0");
        let many = Settings { threads: Some(100_000), ..Default::default() };
        let e = resolve(&[(Origin::Flags, many)]).unwrap_err();
        assert_eq!(e.to_string(), "--threads must be at most 256, got 100000");
        let log = Settings { log: Some(LogTarget::File("/no/such/folder/x.log".into())), ..Default::default() };
        let e = resolve(&[(Origin::Flags, log)]).unwrap_err();
        assert!(
            e.to_string().starts_with("--log-file /no/such/folder/x.log: the folder /no/such/folder does not exist"),
            "{e}"
        );
        let layers = [(Origin::Flags, flags), (file, Settings::of_spec(&spec))];
        assert_eq!(provenance(&layers, "seed").as_deref(), Some("fig.toml: solver.seed"));
        assert_eq!(provenance(&layers, "rel_gap").as_deref(), Some("--gap"));
        assert_eq!(provenance(&layers, "node_limit"), None);
    }
}
