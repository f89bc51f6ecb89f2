//! The annealer over seeds (`netspec level --seeds N`): one record per seed and the figures of
//! the paper's Table 1 over them — the share of seeds that found a first layout and the wanted
//! count, the mean number found, and seconds to the first and to the count of layouts and
//! trials to the count (mean and median over the seeds that got there).

use super::anneal::{self, AnnealOptions, AnnealReport};
use super::cspace::CSpaces;
use super::spec::Level;
use serde::Serialize;

/// One seed's run.
#[derive(Clone, Debug, Serialize)]
pub struct SeedRun {
    /// The seed.
    pub seed: u64,
    /// Distinct layouts found.
    pub layouts: usize,
    /// Seconds to the first layout.
    pub first: Option<f64>,
    /// Seconds to the last layout found.
    pub last: Option<f64>,
    /// Trials made when the last layout was found.
    pub trials: u64,
    /// Why it stopped (`count`, `exhausted`, `time limit`).
    pub stopped: String,
}

/// Mean and median of some runs' figures (`None` when no run got there).
#[derive(Clone, Copy, Debug, Serialize, PartialEq)]
pub struct MeanMedian {
    /// Mean.
    pub mean: f64,
    /// Median (the mean of the middle two for an even number).
    pub median: f64,
    /// Runs it is over.
    pub runs: usize,
}

impl MeanMedian {
    /// Over `xs`, if any.
    pub fn of(mut xs: Vec<f64>) -> Option<MeanMedian> {
        if xs.is_empty() {
            return None;
        }
        xs.sort_by(f64::total_cmp);
        let n = xs.len();
        let median = if n % 2 == 1 { xs[n / 2] } else { (xs[n / 2 - 1] + xs[n / 2]) / 2.0 };
        Some(MeanMedian { mean: xs.iter().sum::<f64>() / n as f64, median, runs: n })
    }
}

/// The annealer over seeds (`summary.json`).
#[derive(Clone, Debug, Serialize)]
pub struct SeedsSummary {
    /// The method summarised (`anneal`).
    pub method: &'static str,
    /// Seeds run (consecutive from the first).
    pub seeds: usize,
    /// Layouts wanted per seed.
    pub count: usize,
    /// Seconds allowed per seed.
    pub time_limit: f64,
    /// Share of seeds with at least one layout.
    pub success_first: f64,
    /// Share of seeds with `count` layouts.
    pub success_count: f64,
    /// Mean number of layouts found.
    pub mean_layouts: f64,
    /// Seconds to the first layout.
    pub time_to_first: Option<MeanMedian>,
    /// Seconds to `count` layouts.
    pub time_to_count: Option<MeanMedian>,
    /// Trials to `count` layouts.
    pub trials_to_count: Option<MeanMedian>,
    /// Every seed's run, in seed order.
    pub runs: Vec<SeedRun>,
}

/// Runs the annealer with seeds `o.seed`, `o.seed + 1`, … (`seeds` in all); returns the first
/// seed's report (its layouts are the ones written) and the summary.
pub fn over_seeds(level: &Level, cs: &CSpaces, o: &AnnealOptions, seeds: usize) -> (AnnealReport, SeedsSummary) {
    let mut first = None;
    let mut runs = Vec::new();
    for k in 0..seeds.max(1) as u64 {
        let seed = o.seed.wrapping_add(k);
        let r = anneal::anneal(level, cs, &AnnealOptions { seed, ..o.clone() });
        runs.push(SeedRun {
            seed,
            layouts: r.layouts.len(),
            first: r.time_to_first,
            last: r.time_to_last,
            trials: r.trials_to_last,
            stopped: r.stopped.clone(),
        });
        first.get_or_insert(r);
    }
    let summary = summarise(&runs, o.count, o.time_limit);
    (first.unwrap_or_default(), summary)
}

/// The figures over some runs.
pub fn summarise(runs: &[SeedRun], count: usize, time_limit: f64) -> SeedsSummary {
    let n = runs.len().max(1) as f64;
    let done: Vec<&SeedRun> = runs.iter().filter(|r| r.layouts >= count).collect();
    SeedsSummary {
        method: "anneal",
        seeds: runs.len(),
        count,
        time_limit,
        success_first: runs.iter().filter(|r| r.layouts > 0).count() as f64 / n,
        success_count: done.len() as f64 / n,
        mean_layouts: runs.iter().map(|r| r.layouts as f64).sum::<f64>() / n,
        time_to_first: MeanMedian::of(runs.iter().filter_map(|r| r.first).collect()),
        time_to_count: MeanMedian::of(done.iter().filter_map(|r| r.last).collect()),
        trials_to_count: MeanMedian::of(done.iter().map(|r| r.trials as f64).collect()),
        runs: runs.to_vec(),
    }
}

/// `x` to two significant digits, trailing zeros dropped (`0.023`, `6.2`, `1`, `230`).
pub fn two_digits(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let e = x.abs().log10().floor() as i32;
    if e >= 1 {
        let unit = 10f64.powi(e - 1);
        return format!("{:.0}", (x / unit).round() * unit);
    }
    let decimals = (1 - e) as usize;
    let t = format!("{x:.decimals$}");
    if t.contains('.') {
        t.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        t
    }
}

fn avg_med(m: Option<MeanMedian>, unit: f64, suffix: &str) -> String {
    m.map_or("–".into(), |m| format!("{}/{}{suffix}", two_digits(m.mean / unit), two_digits(m.median / unit)))
}

/// The summary as a markdown table (the columns of the paper's Table 1).
pub fn table(s: &SeedsSummary) -> String {
    let n = s.count;
    format!(
        "| method | seeds | success first/{n} | #layouts | first, s avg/med | {n} layouts, s avg/med | trials to {n} avg/med |\n\
         |---|---|---|---|---|---|---|\n\
         | {} | {} | {}/{} | {} | {} | {} | {} |\n",
        s.method,
        s.seeds,
        two_digits(s.success_first),
        two_digits(s.success_count),
        two_digits(s.mean_layouts),
        avg_med(s.time_to_first, 1.0, ""),
        avg_med(s.time_to_count, 1.0, ""),
        avg_med(s.trials_to_count, 1000.0, "k"),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(seed: u64, layouts: usize, first: Option<f64>, last: Option<f64>, trials: u64) -> SeedRun {
        SeedRun { seed, layouts, first, last, trials, stopped: String::new() }
    }

    #[test]
    fn figures_count_only_the_seeds_that_got_there() {
        let runs = [
            run(1, 3, Some(1.0), Some(4.0), 100),
            run(2, 1, Some(2.0), Some(2.0), 50),
            run(3, 0, None, None, 0),
            run(4, 3, Some(3.0), Some(6.0), 300),
        ];
        let s = summarise(&runs, 3, 10.0);
        assert_eq!((s.success_first, s.success_count, s.mean_layouts), (0.75, 0.5, 1.75));
        assert_eq!(s.time_to_first, Some(MeanMedian { mean: 2.0, median: 2.0, runs: 3 }));
        assert_eq!(s.time_to_count, Some(MeanMedian { mean: 5.0, median: 5.0, runs: 2 }));
        assert_eq!(s.trials_to_count.map(|m| m.median), Some(200.0));
        assert!(summarise(&runs[2..3], 3, 10.0).time_to_first.is_none());
        let t = table(&s);
        assert!(t.contains("| anneal | 4 | 0.75/0.5 | 1.8 | 2/2 | 5/5 | 0.2/0.2k |"), "{t}");
    }

    #[test]
    fn two_significant_digits() {
        let got: Vec<String> = [0.0234, 6.24, 1.0, 234.0, 0.1, 12.0].map(two_digits).into();
        assert_eq!(got, ["0.023", "6.2", "1", "230", "0.1", "12"]);
    }
}
