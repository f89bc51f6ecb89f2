//! How long a comparison's runs would take on K nodes of C cores: list scheduling of the
//! recorded wall times, longest first, each run on one node holding as many cores as it had
//! threads, started as soon as that many cores of some node are free.

use super::record::RunRecord;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// A cluster shape: `nodes` nodes of `cores` cores each (`20x2`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shape {
    /// Nodes.
    pub nodes: usize,
    /// Cores per node.
    pub cores: u32,
}

impl std::str::FromStr for Shape {
    type Err = String;

    fn from_str(s: &str) -> Result<Shape, String> {
        let bad = || format!("`{s}`: give nodes x cores, as in 20x2");
        let (k, c) = s.split_once(['x', 'X']).ok_or_else(bad)?;
        let nodes: usize = k.trim().parse().map_err(|_| bad())?;
        let cores: u32 = c.trim().parse().map_err(|_| bad())?;
        if nodes == 0 || cores == 0 {
            return Err(format!("`{s}`: nodes and cores must be ≥ 1"));
        }
        Ok(Shape { nodes, cores })
    }
}

/// The estimate for one shape.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Estimate {
    /// The cluster.
    pub shape: Shape,
    /// Seconds from the first start to the last end.
    pub seconds: f64,
    /// Runs scheduled.
    pub runs: usize,
    /// Sum of the runs' wall times, seconds (their time one after another).
    pub serial_seconds: f64,
}

/// Schedules runs of `(seconds, threads)` on `shape` (longest first, each onto the node where
/// its threads' worth of cores is free earliest) and returns the makespan. A run with more
/// threads than a node has cores takes a whole node.
pub fn makespan(runs: &[(f64, u32)], shape: Shape) -> f64 {
    let mut order: Vec<(f64, u32)> = runs.to_vec();
    order.sort_by(|a, b| b.0.total_cmp(&a.0).then(b.1.cmp(&a.1)));
    // Each node's cores, as the times they become free.
    let mut free: Vec<Vec<f64>> = vec![vec![0.0; shape.cores as usize]; shape.nodes];
    let mut end = 0.0f64;
    for (d, t) in order {
        let need = (t.max(1) as usize).min(shape.cores as usize);
        // The earliest start on each node: when its `need`-th earliest core is free.
        let (node, start) = free
            .iter_mut()
            .enumerate()
            .map(|(i, cores)| {
                cores.sort_by(f64::total_cmp);
                (i, cores[need - 1])
            })
            .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)))
            .expect("at least one node");
        for c in free[node].iter_mut().take(need) {
            *c = start + d;
        }
        end = end.max(start + d);
    }
    end
}

/// Estimates for each shape from the records' wall times and threads (a run without a thread
/// count takes one core).
pub fn estimate(records: &[RunRecord], shapes: &[Shape]) -> Vec<Estimate> {
    let runs: Vec<(f64, u32)> = records
        .iter()
        .map(|r| (r.wall_time.max(0.0), r.settings.as_ref().and_then(|s| s.threads).unwrap_or(1)))
        .collect();
    let serial_seconds = runs.iter().map(|r| r.0).sum();
    shapes
        .iter()
        .map(|&shape| Estimate { shape, seconds: makespan(&runs, shape), runs: runs.len(), serial_seconds })
        .collect()
}

/// A duration in words: `42 s`, `12.5 min`, `3.2 h`.
pub fn human(seconds: f64) -> String {
    if seconds < 10.0 {
        format!("{seconds:.1} s")
    } else if seconds < 120.0 {
        format!("{seconds:.0} s")
    } else if seconds < 7200.0 {
        format!("{:.1} min", seconds / 60.0)
    } else {
        format!("{:.1} h", seconds / 3600.0)
    }
}

/// The estimates as a Markdown section.
pub fn markdown(estimates: &[Estimate]) -> String {
    let Some(first) = estimates.first() else { return String::new() };
    let mut s = format!(
        "\nMakespan of these {} runs (list scheduling of their recorded wall times, longest first; one after another: {}):\n\n| nodes × cores | makespan |\n|---|---|\n",
        first.runs,
        human(first.serial_seconds)
    );
    for e in estimates {
        let _ = writeln!(s, "| {} × {} | {} |", e.shape.nodes, e.shape.cores, human(e.seconds));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn list_scheduling() {
        let one = Shape { nodes: 1, cores: 1 };
        assert_eq!(makespan(&[(3.0, 1), (2.0, 1), (1.0, 1)], one), 6.0);
        // 2 cores: 3 | 2+1.
        assert_eq!(makespan(&[(3.0, 1), (2.0, 1), (1.0, 1)], Shape { nodes: 1, cores: 2 }), 3.0);
        // A 2-thread run holds both cores of a node.
        assert_eq!(makespan(&[(4.0, 2), (1.0, 1), (1.0, 1)], Shape { nodes: 1, cores: 2 }), 5.0);
        assert_eq!(makespan(&[(4.0, 2), (1.0, 1), (1.0, 1)], Shape { nodes: 2, cores: 2 }), 4.0);
        assert_eq!(makespan(&[], one), 0.0);
        assert_eq!("20x2".parse::<Shape>(), Ok(Shape { nodes: 20, cores: 2 }));
        assert!("20".parse::<Shape>().is_err() && "0x2".parse::<Shape>().is_err());
    }
}
