//! Recordings (`cutcal recordings`, a project's first step): raw dynamometer force signals -> test rows with their own noise.
//!
//! For each row of the tests CSV the signal `<DIR>/<test>.csv` is streamed through
//! [`cutcal_signal`] (steady window, mean, sd, autocorrelation-aware standard error, drift,
//! oscillation). The tests CSV is written back with the measured forces, `fc_sd_*`/`ft_sd_*`
//! (the sample standard deviation of the force over the steady window) and the covariates
//! `wear_flag` (significant drift) and `bue_flag` (strong low-frequency oscillation). A JSON summary
//! and, with `--plots`, one SVG per test are written too. All outputs are atomic. Methods and
//! sources: docs/recordings.md.

use std::path::{Path, PathBuf};

use std::fmt::Write as _;

use cutcal_io::output::write_atomic;
use cutcal_io::signal_csv::{read_signal, ChannelMap, SignalFile};
use cutcal_io::tests_csv::load_tests;
use cutcal_signal::{analyse, Analysis, AnalysisConfig};
use serde::Serialize;

use crate::bail;
use crate::error::{Context, Error, Result};
use crate::svg::{Plot, Series};

/// Summary of one test.
#[derive(Debug, Clone, Serialize)]
pub struct TestSummary {
    /// Test id.
    pub test: String,
    /// The signal file.
    pub signal: String,
    /// Width of cut, mm.
    pub width_mm: f64,
    /// The analysis (forces in N, totals over the width), or why there is none.
    pub analysis: Option<Analysis>,
    /// Why there is no analysis.
    pub not_available: Option<String>,
}

/// Parses a window `t0,t1` in seconds (`--window`).
pub fn parse_window(s: &str) -> Result<(f64, f64)> {
    let (a, b) = s.split_once(',').with_context(|| format!("--window `{s}`: expected t0,t1 in seconds"))?;
    let t0: f64 = a.trim().parse().with_context(|| format!("--window: `{a}` is not a number"))?;
    let t1: f64 = b.trim().parse().with_context(|| format!("--window: `{b}` is not a number"))?;
    if !(t0.is_finite() && t1.is_finite() && t1 > t0) {
        bail!("--window {t0},{t1}: need finite t0 < t1");
    }
    Ok((t0, t1))
}

/// Every test of a tests file reduced from its signal file.
#[derive(Debug)]
pub struct Recorded {
    /// One summary per row of the tests file.
    pub summaries: Vec<TestSummary>,
    /// The reduced signal of each row, where it has a file.
    pub files: Vec<Option<SignalFile>>,
    /// The tests CSV with the measured columns filled in.
    pub csv: String,
}

/// Reduces the signal `<signals>/<test>.csv` of every row of `tests` (streaming; steady window
/// detected unless `window` is given) and writes the measured columns into the tests CSV text.
/// `shown` names a file in summaries and messages (the command shows the path as given; a
/// project shows it relative to the project, so its outputs carry no absolute path).
///
/// Returns an error if a signal file is malformed (located), or if no row could be measured.
pub fn reduce_signals(
    tests_path: &Path,
    signals: &Path,
    map: &ChannelMap,
    window: Option<(f64, f64)>,
    progress: &dyn crate::Progress,
    shown: &dyn Fn(&Path) -> String,
) -> Result<Recorded> {
    let tests = load_tests(tests_path)?;
    if !signals.is_dir() {
        bail!("signals {}: not a directory", shown(signals));
    }
    let cfg = AnalysisConfig::default();
    let mut summaries = Vec::new();
    let mut files: Vec<Option<SignalFile>> = Vec::new();
    for t in &tests {
        let p = signals.join(format!("{}.csv", t.id));
        let width_mm = t.width_m * 1e3;
        let (analysis, why, file) = if p.is_file() {
            let sig = read_signal(&p, map, |_| {})?;
            match analyse(&sig.reduced, &cfg, window) {
                Ok(an) => (Some(an), None, Some(sig)),
                Err(e) => (None, Some(format!("{}: {e}", shown(&p))), Some(sig)),
            }
        } else {
            (None, Some(format!("no signal file {}", shown(&p))), None)
        };
        summaries.push(TestSummary { test: t.id.clone(), signal: shown(&p), width_mm, analysis, not_available: why });
        files.push(file);
        progress.items("recordings", summaries.len(), tests.len());
    }
    if summaries.iter().all(|s| s.analysis.is_none()) {
        let reasons: Vec<String> = summaries.iter().filter_map(|s| s.not_available.clone()).collect();
        bail!("no test could be measured:\n  {}", reasons.join("\n  "));
    }
    let csv = rewrite_tests_csv(tests_path, &shown(tests_path), &summaries)?;
    Ok(Recorded { summaries, files, csv })
}

/// What `cutcal recordings` writes: the rows, the JSON summary and the plots.
#[derive(Debug)]
pub struct RecordingsOutput {
    /// One summary per row of the tests file.
    pub summaries: Vec<TestSummary>,
    /// The rows CSV written (the JSON summary is beside it, `.json`).
    pub out: PathBuf,
    /// The JSON summary.
    pub json: String,
}

/// Reduces the signals of every row of `tests` (`channels`: `fc=Fz,ft=Fx`; `window`: `t0,t1`)
/// and writes the rows CSV (`out`, default `<tests stem>_measured.csv` beside the input), its
/// JSON summary and, with `plots`, one SVG per reduced test, each atomically.
///
/// Returns an error if an option is malformed, the signals are not a directory, a signal file is
/// malformed (located), no row could be measured, or a file cannot be written.
pub fn record_files(
    tests: &Path,
    signals: &Path,
    out: Option<&Path>,
    plots: Option<&Path>,
    channels: Option<&str>,
    window: Option<&str>,
    progress: &dyn crate::Progress,
) -> Result<RecordingsOutput> {
    let map = match channels {
        Some(s) => ChannelMap::parse(s).map_err(|e| Error::invalid(format!("--channels: {e}")))?,
        None => ChannelMap::default(),
    };
    let window = window.map(parse_window).transpose()?;
    if !signals.is_dir() {
        bail!("--signals {}: not a directory", signals.display());
    }
    let Recorded { summaries, files, csv } =
        reduce_signals(tests, signals, &map, window, progress, &|p| p.display().to_string())?;
    let out = out.map_or_else(|| default_out(tests), Path::to_path_buf);
    write_atomic(&out, csv.as_bytes())?;
    let json = serde_json::to_string_pretty(&summaries)?;
    write_atomic(&out.with_extension("json"), json.as_bytes())?;
    if let Some(dir) = plots {
        for (s, f) in summaries.iter().zip(&files) {
            if let (Some(an), Some(f)) = (&s.analysis, f) {
                write_atomic(&dir.join(format!("{}.svg", s.test)), plot(s, an, f).as_bytes())?;
            }
        }
    }
    Ok(RecordingsOutput { summaries, out, json })
}

fn default_out(tests: &Path) -> PathBuf {
    let stem = tests.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "tests".into());
    tests.with_file_name(format!("{stem}_measured.csv"))
}

fn fmt(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.4}")
    } else {
        String::new()
    }
}

/// The input CSV with the force, sd and flag columns set (added when absent) for measured rows;
/// `shown` names the input in the header comment.
fn rewrite_tests_csv(path: &Path, shown: &str, summaries: &[TestSummary]) -> Result<String> {
    let text = std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let mut rdr = csv::ReaderBuilder::new().comment(Some(b'#')).trim(csv::Trim::All).from_reader(text.as_bytes());
    let mut headers: Vec<String> = rdr.headers()?.iter().map(String::from).collect();
    let totals = headers.iter().any(|h| h == "fc_n" || h == "ft_n");
    let names: [&str; 6] = if totals {
        ["fc_n", "ft_n", "fc_sd_n", "ft_sd_n", "wear_flag", "bue_flag"]
    } else {
        ["fc_n_per_mm", "ft_n_per_mm", "fc_sd_n_per_mm", "ft_sd_n_per_mm", "wear_flag", "bue_flag"]
    };
    let rows: Vec<csv::StringRecord> = rdr.records().collect::<Result<_, _>>()?;
    let chip_sd = chip_sd_from_repeats(&headers, &rows);
    if chip_sd.iter().any(Option::is_some) && !headers.iter().any(|h| h == "chip_sd_mm") {
        headers.push("chip_sd_mm".to_string());
    }
    let old_len = headers.len();
    for n in names {
        if !headers.iter().any(|h| h == n) {
            headers.push(n.to_string());
        }
    }
    let idx = |n: &str| headers.iter().position(|h| h == n).unwrap_or(0);
    let test_col = idx("test");
    let mut w = csv::WriterBuilder::new().from_writer(Vec::new());
    w.write_record(&headers)?;
    for (row, r) in rows.into_iter().enumerate() {
        let mut cells: Vec<String> = r.iter().map(String::from).collect();
        cells.resize(headers.len().max(old_len), String::new());
        if let Some(sd) = chip_sd[row] {
            cells[idx("chip_sd_mm")] = format!("{sd:.5}");
        }
        let id = cells[test_col].clone();
        if let Some(an) =
            summaries.iter().find(|s| s.test == id).and_then(|s| s.analysis.as_ref().map(|a| (a, s.width_mm)))
        {
            let (an, width_mm) = an;
            let scale = if totals { 1.0 } else { 1.0 / width_mm };
            let (fc, ft) = (an.channels[0], an.channels[1]);
            let vals = [
                fmt(fc.mean * scale),
                fmt(ft.mean * scale),
                fmt(fc.sd * scale),
                fmt(ft.sd * scale),
                u8::from(an.possible_tool_wear).to_string(),
                u8::from(an.possible_built_up_edge).to_string(),
            ];
            for (n, v) in names.iter().zip(vals) {
                cells[idx(n)] = v;
            }
        }
        w.write_record(&cells)?;
    }
    let body = String::from_utf8(w.into_inner().map_err(Error::invalid)?)?;
    Ok(format!("# written by cutcal recordings from {shown} (forces: steady-window means; *_sd_*: sample sd over the window)\n{body}"))
}

/// Sample sd of `chip_mm` over rows repeated at one condition (same speed, uncut chip thickness,
/// width and rake cells), per row; `None` for rows without a chip value, without a repeat, or
/// whose repeats are identical.
fn chip_sd_from_repeats(headers: &[String], rows: &[csv::StringRecord]) -> Vec<Option<f64>> {
    let col = |n: &str| headers.iter().position(|h| h == n);
    let (Some(chip), keys) = (col("chip_mm"), ["speed_m_min", "uncut_mm", "width_mm", "rake_deg"].map(col)) else {
        return vec![None; rows.len()];
    };
    let num = |r: &csv::StringRecord, c: Option<usize>| c.and_then(|c| r.get(c)).and_then(|v| v.parse::<f64>().ok());
    let key = |r: &csv::StringRecord| keys.map(|c| num(r, c).map(f64::to_bits));
    let mut out = vec![None; rows.len()];
    for (i, r) in rows.iter().enumerate() {
        if num(r, Some(chip)).is_none() {
            continue;
        }
        let vals: Vec<f64> = rows.iter().filter(|o| key(o) == key(r)).filter_map(|o| num(o, Some(chip))).collect();
        if vals.len() >= 2 {
            let mean = vals.iter().sum::<f64>() / vals.len() as f64;
            let var = vals.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (vals.len() - 1) as f64;
            // Identical repeats say nothing about the spread (a zero sd is not a measurement).
            out[i] = Some(var.sqrt()).filter(|v| *v > 0.0);
        }
    }
    out
}

/// The SVG of one test: Fc, Ft envelopes, the window and the Fc mean +- sd band.
#[must_use]
pub fn plot(s: &TestSummary, an: &Analysis, f: &SignalFile) -> String {
    let r = &f.reduced;
    let step = r.len().div_ceil(2000).max(1);
    let pts = |c: usize| -> Vec<(f64, f64)> {
        (0..r.len())
            .step_by(step)
            .filter(|&k| r.blocks[c][k].moments.n > 0)
            .map(|k| (r.block_mid_s(k), r.blocks[c][k].moments.mean))
            .collect()
    };
    let fc = an.channels[0];
    let ymax = r.blocks[0].iter().map(|b| b.moments.mean).fold(0.0f64, f64::max);
    let band = |y: f64| vec![(an.t0_s, y), (an.t1_s, y)];
    let series = vec![
        Series::line("Fc (N)", pts(0)),
        Series::line("Ft (N)", pts(1)),
        Series::dashed("Fc mean + sd", band(fc.mean + fc.sd)),
        Series::dashed("Fc mean - sd", band(fc.mean - fc.sd)),
        Series::dashed("window start", vec![(an.t0_s, 0.0), (an.t0_s, ymax)]),
        Series::dashed("window end", vec![(an.t1_s, 0.0), (an.t1_s, ymax)]),
    ];
    Plot {
        title: format!("test {}: steady window {:.3}-{:.3} s", s.test, an.t0_s, an.t1_s),
        x_label: "time (s)".into(),
        y_label: "force (N)".into(),
        series,
        diagonal: false,
    }
    .render()
}

/// The readable table of `cutcal recordings`, ending with the files written.
#[must_use]
pub fn table(r: &RecordingsOutput) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<8} {:>15} {:>10} {:>8} {:>8} {:>10} {:>8} {:>5} {:>5}",
        "test", "window (s)", "Fc (N)", "sd", "se", "Ft (N)", "sd", "wear", "BUE"
    );
    for t in &r.summaries {
        let _ = match &t.analysis {
            Some(a) => writeln!(
                s,
                "{:<8} {:>7.3}-{:<7.3} {:>10.2} {:>8.2} {:>8.3} {:>10.2} {:>8.2} {:>5} {:>5}",
                t.test,
                a.t0_s,
                a.t1_s,
                a.channels[0].mean,
                a.channels[0].sd,
                a.channels[0].se,
                a.channels[1].mean,
                a.channels[1].sd,
                if a.possible_tool_wear { "yes" } else { "no" },
                if a.possible_built_up_edge { "yes" } else { "no" }
            ),
            None => writeln!(s, "{:<8} not available: {}", t.test, t.not_available.as_deref().unwrap_or("")),
        };
    }
    let _ = writeln!(s, "wrote {} and {}", r.out.display(), r.out.with_extension("json").display());
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chip_sd_comes_from_repeats_at_one_condition_only() {
        // Three repeats of 0.30, 0.32, 0.34 mm: mean 0.32, sample sd sqrt((0.02^2 * 2) / 2) = 0.02.
        let headers: Vec<String> =
            ["test", "speed_m_min", "uncut_mm", "width_mm", "rake_deg", "chip_mm"].map(String::from).to_vec();
        let rows: Vec<csv::StringRecord> = [
            ["a", "240", "0.075", "1.95", "0", "0.30"],
            ["b", "240", "0.075", "1.95", "0", "0.32"],
            ["c", "240", "0.075", "1.95", "0", "0.34"],
            ["d", "180", "0.075", "1.95", "0", "0.40"],
            ["e", "240", "0.075", "1.95", "0", ""],
        ]
        .iter()
        .map(|r| csv::StringRecord::from(r.to_vec()))
        .collect();
        let sd = chip_sd_from_repeats(&headers, &rows);
        for s in &sd[..3] {
            assert!((s.unwrap() - 0.02).abs() < 1e-12, "{sd:?}");
        }
        assert_eq!(sd[3], None);
        assert_eq!(sd[4], None);
    }
}
