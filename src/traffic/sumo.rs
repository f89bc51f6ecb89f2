//! Finding SUMO and running its tools (`netconvert`, `duarouter`, `sumo`), each with its whole
//! output kept in a log file next to its results.
//!
//! SUMO is looked for, in order: the directory given (`--sumo-home`), `$SUMO_HOME`, the copy
//! `scripts/setup.sh` installs (`<deps>/sumo-home`, `<deps>` being `$NETSPEC_DEPS`, else
//! `$XDG_CACHE_HOME/netspec`, else `~/.cache/netspec`), and `sumo` on `PATH`.

use super::export::PlainFiles;
use super::{DemandSettings, TrafficError, TrafficErrorKind};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The SUMO version `scripts/setup.sh` installs (the `eclipse-sumo` wheel).
pub const SETUP_SUMO_VERSION: &str = "1.28.0";

/// A SUMO installation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Sumo {
    /// The directory with `sumo`, `netconvert` and `duarouter`.
    pub bin: PathBuf,
    /// `SUMO_HOME` (data and tools), if known.
    pub home: Option<PathBuf>,
    /// The version `sumo --version` reports.
    pub version: String,
    /// When the command's time runs out: a tool still running then is killed, and the
    /// evaluation ends with [`TrafficErrorKind::TimeLimit`] (`None`: no limit).
    #[serde(skip)]
    pub deadline: Option<std::time::Instant>,
}

/// Where `scripts/setup.sh` puts SUMO: `<deps>/sumo-home`.
pub fn setup_location() -> Option<PathBuf> {
    let env = |k: &str| std::env::var_os(k).filter(|v| !v.is_empty()).map(PathBuf::from);
    let deps = env("NETSPEC_DEPS")
        .or_else(|| env("XDG_CACHE_HOME").map(|c| c.join("netspec")))
        .or_else(|| env("HOME").map(|h| h.join(".cache").join("netspec")))?;
    Some(deps.join("sumo-home"))
}

impl Sumo {
    /// Finds SUMO (see the module docs); `home` is an explicit `SUMO_HOME`, used alone.
    pub fn locate(home: Option<&Path>) -> Result<Sumo, TrafficError> {
        if let Some(h) = home {
            // Asked for by name: that one or an error.
            let bin = h.join("bin");
            if !bin.join("sumo").is_file() {
                return Err(TrafficError::new(h, TrafficErrorKind::SumoMissing { looked: bin.display().to_string() }));
            }
            return Sumo::at(bin, Some(h.to_path_buf()));
        }
        let mut looked = Vec::new();
        let mut homes: Vec<PathBuf> = Vec::new();
        homes.extend(std::env::var_os("SUMO_HOME").filter(|v| !v.is_empty()).map(PathBuf::from));
        homes.extend(setup_location());
        for h in homes {
            let bin = h.join("bin");
            if bin.join("sumo").is_file() {
                return Sumo::at(bin, Some(h));
            }
            looked.push(bin.display().to_string());
        }
        if let Some(dir) =
            std::env::var_os("PATH").and_then(|p| std::env::split_paths(&p).find(|d| d.join("sumo").is_file()))
        {
            let home = Some(PathBuf::from("/usr/share/sumo")).filter(|h| h.join("data").is_dir());
            return Sumo::at(dir, home);
        }
        looked.push("PATH".into());
        Err(TrafficError::new("sumo", TrafficErrorKind::SumoMissing { looked: looked.join(", ") }))
    }

    /// SUMO with its binaries in `bin`; asks `sumo --version`.
    pub fn at(bin: PathBuf, home: Option<PathBuf>) -> Result<Sumo, TrafficError> {
        let exe = bin.join("sumo");
        let out = Command::new(&exe).arg("--version").output().map_err(|e| TrafficError::new(&exe, e.into()))?;
        let text = String::from_utf8_lossy(&out.stdout);
        let first = text.lines().next().unwrap_or_default();
        let version = first
            .split_whitespace()
            .rev()
            .find(|w| w.chars().next().is_some_and(|c| c.is_ascii_digit()) && w.contains('.'))
            .map(str::to_string)
            .ok_or_else(|| {
                TrafficError::new(
                    &exe,
                    TrafficErrorKind::Output(format!("`sumo --version` printed no version: {first:?}")),
                )
            })?;
        Ok(Sumo { bin, home, version, deadline: None })
    }

    /// Runs one tool; its output goes to `log`. `input` is named in errors.
    fn run(&self, tool: &str, args: &[String], input: &Path, log: &Path) -> Result<(), TrafficError> {
        let exe = self.bin.join(tool);
        let mut cmd = Command::new(&exe);
        cmd.args(args);
        if let Some(h) = &self.home {
            cmd.env("SUMO_HOME", h);
        }
        let status = self.run_until_deadline(tool, &exe, &mut cmd, args, log)?;
        let text = super::read(log)?;
        if status.success() {
            return Ok(());
        }
        let errors: Vec<&str> = text.lines().filter(|l| l.starts_with("Error")).collect();
        let detail = if errors.is_empty() {
            text.lines().rev().take(3).collect::<Vec<_>>().into_iter().rev().collect::<Vec<_>>().join(" / ")
        } else {
            errors[..errors.len().min(3)].join(" / ")
        };
        Err(TrafficError::new(
            input,
            TrafficErrorKind::ToolFailed {
                tool: tool.into(),
                status: status.to_string(),
                detail,
                log: log.to_path_buf(),
            },
        ))
    }

    /// Runs `cmd` with its output into `log` (after the command line), killed at the deadline.
    fn run_until_deadline(
        &self,
        tool: &str,
        exe: &Path,
        cmd: &mut Command,
        args: &[String],
        log: &Path,
    ) -> Result<std::process::ExitStatus, TrafficError> {
        let io = |e: std::io::Error| TrafficError::new(log, e.into());
        super::write(log, &format!("$ {} {}\n", exe.display(), args.join(" ")))?;
        let file = std::fs::OpenOptions::new().append(true).open(log).map_err(io)?;
        cmd.stdout(file.try_clone().map_err(io)?).stderr(file);
        let mut child = cmd.spawn().map_err(|e| TrafficError::new(exe, e.into()))?;
        loop {
            if let Some(status) = child.try_wait().map_err(io)? {
                return Ok(status);
            }
            if self.deadline.is_some_and(|d| std::time::Instant::now() >= d) {
                let _ = child.kill();
                let _ = child.wait();
                return Err(TrafficError::new(exe, TrafficErrorKind::TimeLimit { tool: tool.into() }));
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
    }

    /// `netconvert`: plain XML to `net` (coordinates kept as given; U-turns only at dead ends).
    pub fn netconvert(&self, files: &PlainFiles, net: &Path) -> Result<(), TrafficError> {
        let p = |p: &Path| p.display().to_string();
        let args = vec![
            "--node-files".into(),
            p(&files.nodes),
            "--edge-files".into(),
            p(&files.edges),
            "--type-files".into(),
            p(&files.types),
            "--output-file".into(),
            p(net),
            "--offset.disable-normalization".into(),
            "true".into(),
            "--no-turnarounds.except-deadend".into(),
            "true".into(),
        ];
        self.run("netconvert", &args, &files.edges, &net.with_extension("log"))
    }

    /// `duarouter`: the fastest route (free-flow travel times) of every trip (trips between
    /// junctions leave and reach them on any edge); trips without a route are dropped (and
    /// counted by the caller).
    pub fn duarouter(&self, net: &Path, trips: &Path, routes: &Path, seed: u64) -> Result<(), TrafficError> {
        let p = |p: &Path| p.display().to_string();
        let args = vec![
            "--net-file".into(),
            p(net),
            "--route-files".into(),
            p(trips),
            "--output-file".into(),
            p(routes),
            "--seed".into(),
            seed.to_string(),
            "--ignore-errors".into(),
            "true".into(),
            "--junction-taz".into(),
            "true".into(),
            "--no-step-log".into(),
            "true".into(),
        ];
        self.run("duarouter", &args, trips, &routes.with_extension("log"))
    }

    /// `sumo` headless: the routes from time 0 until every vehicle has left, or at most one
    /// hour after the last departure window (`duration + 3600` s); writes the outputs into
    /// `dir`.
    pub fn simulate(
        &self,
        net: &Path,
        routes: &Path,
        dir: &Path,
        demand: &DemandSettings,
    ) -> Result<SimOutputs, TrafficError> {
        let o = SimOutputs {
            tripinfo: dir.join("tripinfo.xml"),
            edgedata: dir.join("edgedata.xml"),
            vehroutes: dir.join("vehroutes.xml"),
            statistics: dir.join("statistics.xml"),
            log: dir.join("sumo.log"),
        };
        let p = |p: &Path| p.display().to_string();
        let args = vec![
            "--net-file".into(),
            p(net),
            "--route-files".into(),
            p(routes),
            "--tripinfo-output".into(),
            p(&o.tripinfo),
            "--edgedata-output".into(),
            p(&o.edgedata),
            "--vehroute-output".into(),
            p(&o.vehroutes),
            "--statistic-output".into(),
            p(&o.statistics),
            "--seed".into(),
            demand.seed.to_string(),
            "--begin".into(),
            "0".into(),
            "--end".into(),
            format!("{}", demand.duration + 3600.0),
            "--time-to-teleport".into(),
            "300".into(),
            "--no-step-log".into(),
            "true".into(),
        ];
        self.run("sumo", &args, routes, &o.log)?;
        Ok(o)
    }
}

/// The files a simulation wrote.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SimOutputs {
    /// One `tripinfo` per vehicle that arrived.
    pub tripinfo: PathBuf,
    /// Per edge: vehicles departed, entered, arrived, left, and more.
    pub edgedata: PathBuf,
    /// Every vehicle's route as driven.
    pub vehroutes: PathBuf,
    /// Vehicles loaded, inserted, running; teleports.
    pub statistics: PathBuf,
    /// `sumo`'s own output.
    pub log: PathBuf,
}
