//! Timing: warm-up runs, then the median (with min and max) of N timed runs.

use web_time::Instant;

/// The machine a time is measured on, as a time's cache key needs it: the CPU's model name
/// (Linux's `/proc/cpuinfo`; the architecture elsewhere) and the threads a render uses.
pub fn machine() -> String {
    let model = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|info| {
            info.lines().find_map(|l| l.strip_prefix("model name").and_then(|r| r.split_once(':')).map(|(_, m)| m.trim().to_string()))
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    format!("{model}, {} threads", rayon::current_num_threads())
}

/// Summary of repeated timings, in milliseconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    /// Median of the timed runs.
    pub median_ms: f64,
    /// Fastest run.
    pub min_ms: f64,
    /// Slowest run.
    pub max_ms: f64,
    /// Number of timed runs.
    pub runs: usize,
    /// How far the runs disagree, robust to one slow run, as a share of the median: the
    /// middle half's width (the 3rd minus the 1st quartile) from four runs on; for three,
    /// twice the smaller gap to the median; for two, their difference; 0 for one.
    pub spread: f64,
}

/// Runs `f` `warmup` times untimed, then `runs` times timed (`runs` ≥ 1).
///
/// The median, not the mean, because one descheduled run on a shared machine would
/// otherwise move the figure.
pub fn time<T>(warmup: usize, runs: usize, f: impl FnMut() -> T) -> Timing {
    time_within(warmup, runs, None, f)
}

/// Timed runs a budget never cuts below: the median of three is the first that one slow
/// run cannot move.
pub const MIN_RUNS: usize = 3;

/// Two consecutive runs within this share of each other settle a budgeted median.
pub const AGREE: f64 = 0.02;

/// [`time`] with a time budget: with `budget_ms`, the timed runs stop as soon as two
/// consecutive runs agree to [`AGREE`] (the median is then known to 2%: a descheduled or
/// cold run would not agree with the next), or once at least [`MIN_RUNS`] have run and
/// together they took `budget_ms` or more; `runs` is the most (a slow, steady rung gets
/// two or three runs, a fast noisy one `runs`).
pub fn time_within<T>(warmup: usize, runs: usize, budget_ms: Option<f64>, f: impl FnMut() -> T) -> Timing {
    time_keeping(warmup, runs, budget_ms, f).0
}

/// [`time_within`], keeping what the last run returned: a deterministic computation timed
/// this way needs no extra run for its result.
pub fn time_keeping<T>(warmup: usize, runs: usize, budget_ms: Option<f64>, mut f: impl FnMut() -> T) -> (Timing, T) {
    for _ in 0..warmup {
        std::hint::black_box(f());
    }
    let mut ms: Vec<f64> = Vec::with_capacity(runs.max(1));
    let mut last = None;
    while ms.len() < runs.max(1) {
        let start = Instant::now();
        let out = std::hint::black_box(f());
        ms.push(start.elapsed().as_secs_f64() * 1e3);
        // Dropped outside the timed span, as the rung's frame would be.
        last = Some(out);
        if budget_ms.is_some_and(|b| settled(&ms, b)) {
            break;
        }
    }
    (summarize(&mut ms), last.expect("at least one run"))
}

/// True when the runs `ms` (in order) need no more under the budget `budget_ms`: the last
/// two agree to [`AGREE`], or [`MIN_RUNS`] or more took the budget.
fn settled(ms: &[f64], budget_ms: f64) -> bool {
    let n = ms.len();
    let agree = n >= 2 && (ms[n - 1] - ms[n - 2]).abs() <= AGREE * 0.5 * (ms[n - 1] + ms[n - 2]);
    agree || (n >= MIN_RUNS && ms.iter().sum::<f64>() >= budget_ms)
}

/// Median, min and max of measurements (sorted in place).
pub fn summarize(ms: &mut [f64]) -> Timing {
    ms.sort_by(f64::total_cmp);
    let n = ms.len();
    let median = if n == 0 {
        0.0
    } else if n % 2 == 1 {
        ms[n / 2]
    } else {
        0.5 * (ms[n / 2 - 1] + ms[n / 2])
    };
    let width = match n {
        0 | 1 => 0.0,
        2 => ms[1] - ms[0],
        3 => 2.0 * (ms[1] - ms[0]).min(ms[2] - ms[1]),
        _ => ms[(3 * n) / 4] - ms[n / 4],
    };
    let spread = if median > 0.0 { width / median } else { 0.0 };
    Timing { median_ms: median, min_ms: ms.first().copied().unwrap_or(0.0), max_ms: ms.last().copied().unwrap_or(0.0), runs: n, spread }
}

/// Resets the process's peak resident memory to its current size (Linux: `5` written to
/// /proc/self/clear_refs), so [`peak_rss_mb`] measures what follows; a no-op elsewhere.
pub fn reset_peak_rss() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

/// Peak resident memory of this process in MB (VmHWM), where the OS reports it.
pub fn peak_rss_mb() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_spread_ignores_one_slow_run_but_not_a_busy_machine() {
        // One descheduled run among five: the middle half agrees.
        assert!(summarize(&mut [10.0, 10.2, 9.9, 30.0, 10.1]).spread < 0.05);
        // Lesson 15's flat rung on a busy machine: the runs themselves scattered.
        assert!(summarize(&mut [3.4, 34.8, 30.0, 64.9, 20.0]).spread > 0.25);
        // Three runs: one outlier is forgiven, two are not.
        assert!(summarize(&mut [10.0, 10.1, 25.0]).spread < 0.05);
        assert!(summarize(&mut [5.0, 10.0, 15.0]).spread > 0.25);
        assert!((summarize(&mut [4.0, 8.0]).spread - 4.0 / 6.0).abs() < 1e-12);
        assert_eq!(summarize(&mut [4.0]).spread, 0.0);
    }

    #[test]
    fn a_budget_stops_slow_runs_at_three_and_lets_fast_ones_run_their_count() {
        // Runs that never agree to 2%: 20, 30, 20, 30 ... ms.
        let mut k = 0;
        let slow = time_within(0, 10, Some(50.0), || {
            k += 1;
            std::thread::sleep(std::time::Duration::from_millis(if k % 2 == 1 { 20 } else { 30 }))
        });
        assert_eq!(slow.runs, MIN_RUNS);
        // Runs alternating between 1 µs and 100 µs never agree and never fill the budget.
        let mut k = 0;
        let fast = time_within(0, 5, Some(50.0), || {
            k += 1;
            std::thread::sleep(std::time::Duration::from_micros(if k % 2 == 1 { 1 } else { 100 }))
        });
        assert_eq!(fast.runs, 5);
        // Two consecutive runs within 2% settle it; a cold first run does not agree.
        assert!(settled(&[100.0, 101.5], 1e9));
        assert!(!settled(&[130.0, 100.0], 1e9));
        assert!(settled(&[130.0, 100.0, 101.0], 1e9));
        assert!(!settled(&[100.0, 110.0, 100.0], 1e9));
        assert!(settled(&[100.0, 110.0, 100.0], 300.0));
        // Without a budget, every run asked for.
        assert_eq!(time_within(0, 4, None, || std::thread::sleep(std::time::Duration::from_millis(20))).runs, 4);
    }

    use super::*;

    #[test]
    fn median_min_max() {
        let t = summarize(&mut [5.0, 1.0, 9.0, 3.0, 7.0]);
        assert_eq!((t.median_ms, t.min_ms, t.max_ms, t.runs), (5.0, 1.0, 9.0, 5));
        assert_eq!(summarize(&mut [4.0, 1.0, 2.0, 3.0]).median_ms, 2.5);
        let mut calls = 0;
        let t = time(2, 3, || calls += 1);
        assert_eq!((calls, t.runs), (5, 3));
    }
}
