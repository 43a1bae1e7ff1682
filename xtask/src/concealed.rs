//! `cargo xtask concealed`: an independent concealed-physics benchmark of `cutcal diagnose`
//! (issue 10, item 5).
//!
//! The generator shares no model code with the detector: three forward models written here from the
//! literature (family `a`: Oxley 1989 as in Lalwani et al. 2009, `oxley.rs`; family `b`: Merchant
//! closure + Zorev contact + Loewen-Shaw temperatures, `merchant.rs`; family `c`: minimum-energy
//! shear angle + Coulomb-Tresca contact + Weiner / Jaeger temperatures, `energy.rs`), the hidden mechanisms in
//! published forms other than the detector's (`mechanism.rs`; family `d`: a's closure with every
//! mechanism in a third form, `forms_d.rs`), datasets as a user has them
//! (`dataset.rs`). Each dataset is diagnosed in Mode A exactly as `cutcal diagnose --recordings
//! recordings.csv --simulation simulation.csv --json` would (the CLI's own argument parser and
//! `diagnose_files`), and only `verdict`, `selected`, `ambiguous_with` and `fit.{before,after}.loco.all`
//! are read from the JSON report. Scores: `score.rs`; the docs page: `page.rs`.
//!
//! Output directory: `data/<family>/<NNN>/{recordings,simulation}.csv`, `truth-<family>.json` (sealed:
//! never read by the diagnosis), `outcomes-<family>.json`, `scores.json`, `summary.md`. With
//! `--generate-only`: `data/` and `truth-<family>.json` only, and a generation summary on stderr.

mod dataset;
mod detectable;
mod energy;
mod forms_d;
mod material;
mod mechanism;
mod merchant;
mod oxley;
mod page;
mod score;

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context as _, Result};
use clap::Parser as _;
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

pub use material::NuisanceScope;
use mechanism::{DECOYS, MECHANISMS};
use score::Outcome;

/// Options of the benchmark.
#[derive(Debug, Clone)]
pub struct ConcealedOptions {
    /// Families to run.
    pub families: Vec<Family>,
    /// Datasets per family.
    pub datasets: usize,
    /// Seed.
    pub seed: u64,
    /// Output directory.
    pub out: PathBuf,
    /// Markdown page (e.g. docs/concealed.md), if any.
    pub markdown: Option<PathBuf>,
    /// Worker threads.
    pub threads: usize,
    /// Force this work material on every dataset (the material-spread check), by name.
    pub material: Option<String>,
    /// Generate the data and the sealed truth only (no diagnosis, no outcomes, scores or page).
    pub generate_only: bool,
    /// Which constants each dataset's nuisance perturbs (the headline: `Full`).
    pub nuisance: material::NuisanceScope,
}

/// A generator family: `a` (Oxley; the detector may be tuned on it), `b` (Merchant closure, Zorev
/// contact, Loewen-Shaw temperatures; never tuned on), `c` (Merchant's minimum-energy shear angle,
/// Coulomb-Tresca contact, Weiner / Jaeger temperatures, `energy.rs`; never tuned on) or `d`
/// (family a's Oxley closure with every mechanism in a third form, `forms_d.rs`; never tuned on,
/// generated blind).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// Oxley 1989 (`oxley.rs`).
    A,
    /// Merchant + Zorev + Loewen-Shaw (`merchant.rs`).
    B,
    /// Minimum energy + Coulomb-Tresca + Weiner / Jaeger (`energy.rs`).
    C,
    /// Oxley 1989 (`oxley.rs`) with the mechanisms of `forms_d.rs`.
    D,
}

impl Family {
    /// `a`, `b`, `c` or `d`.
    pub const fn as_str(self) -> &'static str {
        match self {
            Self::A => "a",
            Self::B => "b",
            Self::C => "c",
            Self::D => "d",
        }
    }

    /// The families of a `--family` value: `a`, `b`, `c`, `d`, `both` (= a and b), `all` (= a, b,
    /// c; not d) or a comma list of single families such as `a,b,c,d` (no repeats).
    pub fn parse_list(s: &str) -> Result<Vec<Self>, String> {
        let one = |x: &str| [Self::A, Self::B, Self::C, Self::D].into_iter().find(|f| f.as_str() == x.trim());
        let err = || {
            format!("--family must be a, b, c, d, both (a and b), all (a, b, c) or a comma list such as a,b,c,d (got `{s}`)")
        };
        Ok(match s {
            "both" | "ab" => vec![Self::A, Self::B],
            "all" | "abc" => vec![Self::A, Self::B, Self::C],
            list => {
                let fams: Vec<Self> = list.split(',').map(one).collect::<Option<_>>().ok_or_else(err)?;
                let repeated = fams.iter().enumerate().any(|(i, f)| fams[..i].contains(f));
                (!repeated).then_some(fams).ok_or_else(err)?
            }
        })
    }

    /// Offset of the family's random stream in a dataset's seed: a and b keep the streams they had
    /// before family c existed (0 and 2^32); c has its own (2^33), d its own (3 * 2^32).
    pub const fn stream(self) -> u64 {
        match self {
            Self::A => 0,
            Self::B => 1 << 32,
            Self::C => 2 << 32,
            Self::D => 3 << 32,
        }
    }
}

/// Kinds of the `n` datasets of a family, in a seeded shuffled order: nulls, each mechanism and each
/// decoy in the proportion 56 : 14 (each of 8) : 8 (each of 4), largest remainders first. For
/// n = 200: 56 nulls, 14 per mechanism, 8 per decoy (58, 14-15 and 8-9 before the forty-eighth
/// session's fourth decoy).
pub fn kinds(n: usize, seed: u64) -> Vec<String> {
    let mut groups: Vec<(String, f64)> = vec![("null".into(), 56.0)];
    groups.extend(MECHANISMS.iter().map(|m| (m.to_string(), 14.0)));
    groups.extend(DECOYS.iter().map(|d| (d.to_string(), 8.0)));
    let total: f64 = groups.iter().map(|g| g.1).sum();
    let exact: Vec<f64> = groups.iter().map(|g| g.1 * n as f64 / total).collect();
    let mut count: Vec<usize> = exact.iter().map(|x| x.floor() as usize).collect();
    let mut order: Vec<usize> = (0..groups.len()).collect();
    order.sort_by(|&a, &b| (exact[b] - exact[b].floor()).total_cmp(&(exact[a] - exact[a].floor())).then(a.cmp(&b)));
    let mut left = n - count.iter().sum::<usize>();
    for &i in order.iter().cycle() {
        if left == 0 {
            break;
        }
        count[i] += 1;
        left -= 1;
    }
    let mut v: Vec<String> = groups.iter().zip(&count).flat_map(|(g, &c)| (0..c).map(|_| g.0.clone())).collect();
    v.shuffle(&mut ChaCha8Rng::seed_from_u64(seed ^ 0x5EED));
    v
}

/// Mode A diagnosis as the CLI runs it; returns the report as JSON.
fn diagnose(recordings: &Path, simulation: &Path) -> Result<serde_json::Value> {
    #[derive(clap::Parser)]
    struct Cli {
        #[command(flatten)]
        args: cutcal_cli::commands::diagnose::DiagnoseArgs,
    }
    let argv = [
        "diagnose".as_ref(),
        "--recordings".as_ref(),
        recordings.as_os_str(),
        "--simulation".as_ref(),
        simulation.as_os_str(),
        "--json".as_ref(),
    ];
    let cli = Cli::try_parse_from(argv).context("building the diagnose arguments")?;
    let report = cutcal_report::diagnose::diagnose_files(&cli.args.request())?;
    Ok(serde_json::to_value(&report)?)
}

fn strings(v: &serde_json::Value, key: &str) -> Vec<String> {
    v.get(key)
        .and_then(|x| x.as_array())
        .map_or_else(Vec::new, |a| a.iter().filter_map(|s| s.as_str().map(str::to_string)).collect())
}

/// Generates, writes and diagnoses one dataset; never drops it.
fn one(
    family: Family,
    index: usize,
    hidden: &str,
    rank: usize,
    opts: &ConcealedOptions,
) -> (Outcome, Option<dataset::Truth>) {
    let mut o = Outcome {
        family: family.as_str().into(),
        index,
        hidden: hidden.into(),
        enr: None,
        enr_shape: None,
        enr_beyond_nuisance: None,
        rival_chi2: None,
        nearest_rival: None,
        status: "generation_failed".into(),
        reason: String::new(),
        verdict: None,
        selected: Vec::new(),
        ambiguous_with: Vec::new(),
        loco_before: None,
        loco_after: None,
        shadow_rms_pct: None,
        seconds: 0.0,
    };
    let material = opts.material.as_deref().and_then(material::by_name);
    let ds = match dataset::generate(family, index, hidden, rank, opts.seed, material, opts.nuisance) {
        Ok(d) => d,
        Err(e) => {
            o.reason = e;
            return (o, None);
        }
    };
    o.enr = Some(ds.truth.enr);
    o.enr_shape = Some(ds.truth.enr_shape);
    o.enr_beyond_nuisance = ds.truth.enr_beyond_nuisance;
    o.rival_chi2 = ds.truth.rival_chi2;
    o.nearest_rival.clone_from(&ds.truth.nearest_rival);
    let dir = opts.out.join("data").join(family.as_str()).join(format!("{index:03}"));
    let (rec, sim) = (dir.join("recordings.csv"), dir.join("simulation.csv"));
    let written = std::fs::create_dir_all(&dir)
        .and_then(|()| std::fs::write(&rec, &ds.recordings))
        .and_then(|()| std::fs::write(&sim, &ds.simulation));
    if let Err(e) = written {
        o.reason = format!("writing {}: {e}", dir.display());
        return (o, Some(ds.truth));
    }
    if opts.generate_only {
        o.status = "generated".into();
        return (o, Some(ds.truth));
    }
    let t0 = Instant::now();
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| diagnose(&rec, &sim)));
    o.seconds = t0.elapsed().as_secs_f64();
    match result {
        Ok(Ok(v)) => {
            o.status = "ok".into();
            o.verdict = v.get("verdict").and_then(|x| x.as_str()).map(str::to_string);
            o.selected = strings(&v, "selected");
            o.ambiguous_with = strings(&v, "ambiguous_with");
            let loco = |which: &str| v.pointer(&format!("/fit/{which}/loco/all")).and_then(serde_json::Value::as_f64);
            o.loco_before = loco("before");
            o.loco_after = loco("after");
            o.shadow_rms_pct = v.get("shadow_rms_pct").and_then(serde_json::Value::as_f64);
            let _ = std::fs::write(dir.join("report.json"), serde_json::to_string_pretty(&v).unwrap_or_default());
        }
        Ok(Err(e)) => {
            o.status = "diagnosis_error".into();
            o.reason = format!("{e:#}");
        }
        Err(_) => {
            o.status = "diagnosis_error".into();
            o.reason = "the diagnosis panicked".into();
        }
    }
    (o, Some(ds.truth))
}

/// Runs one family; returns its outcomes and truths.
pub fn run_family(family: Family, opts: &ConcealedOptions, quiet: bool) -> (Vec<Outcome>, Vec<dataset::Truth>) {
    let ks = kinds(opts.datasets, opts.seed);
    let jobs: Vec<(usize, &str, usize)> =
        ks.iter().enumerate().map(|(i, k)| (i, k.as_str(), ks[..i].iter().filter(|x| *x == k).count())).collect();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let res: Vec<(Outcome, Option<dataset::Truth>)> = jobs
        .par_iter()
        .map(|&(i, k, rank)| {
            let r = one(family, i, k, rank, opts);
            let d = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            if !quiet && ((d - 1) % 10 == 9 || d == jobs.len()) {
                eprintln!("family {}: {d}/{} datasets", family.as_str(), jobs.len());
            }
            r
        })
        .collect();
    let truths = res.iter().filter_map(|r| r.1.clone()).collect();
    (res.into_iter().map(|r| r.0).collect(), truths)
}

/// `cargo xtask concealed`.
pub fn run(opts: &ConcealedOptions) -> Result<()> {
    if opts.families.is_empty() {
        bail!("no family to run");
    }
    if opts.datasets == 0 {
        bail!("--datasets must be at least 1");
    }
    if opts.nuisance != NuisanceScope::Full && opts.markdown.is_some() {
        bail!("--markdown: the page describes the full nuisance; a `--nuisance eta-psi` run writes its summary only");
    }
    if let Some(m) = opts.material.as_deref() {
        if material::by_name(m).is_none() {
            bail!("--material: no material named `{m}` (AISI1045, AISI4340, Ti6Al4V, AA2024-T351, OFHC-Cu, Nickel200)");
        }
    }
    std::fs::create_dir_all(&opts.out).with_context(|| format!("creating {}", opts.out.display()))?;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(opts.threads.max(1)).build()?;
    let t0 = Instant::now();
    let mut sections = Vec::new();
    let mut heads = Vec::new();
    for &fam in &opts.families {
        let f = fam.as_str();
        let (outcomes, truths) = pool.install(|| run_family(fam, opts, false));
        std::fs::write(opts.out.join(format!("truth-{f}.json")), serde_json::to_string_pretty(&truths)?)?;
        if opts.generate_only {
            eprint!("{}", score::generation_summary(f, &outcomes));
            continue;
        }
        std::fs::write(opts.out.join(format!("outcomes-{f}.json")), serde_json::to_string_pretty(&outcomes)?)?;
        let (text, head) = score::summarise(f, &outcomes);
        sections.push((fam, text));
        heads.push(head);
    }
    if opts.generate_only {
        return Ok(());
    }
    let md = page::render(opts, &sections, t0.elapsed().as_secs_f64());
    std::fs::write(opts.out.join("summary.md"), &md)?;
    std::fs::write(opts.out.join("scores.json"), serde_json::to_string_pretty(&heads)?)?;
    if let Some(p) = &opts.markdown {
        std::fs::write(p, &md).with_context(|| format!("writing {}", p.display()))?;
    }
    println!("{md}");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(csv: &str) -> Vec<Vec<String>> {
        csv.lines().skip(1).map(|l| l.split(',').map(str::to_string).collect()).collect()
    }

    #[test]
    fn family_flags_and_streams() {
        assert_eq!(Family::parse_list("both").unwrap(), [Family::A, Family::B]);
        assert_eq!(Family::parse_list("all").unwrap(), [Family::A, Family::B, Family::C]);
        assert_eq!(Family::parse_list("c").unwrap(), [Family::C]);
        assert_eq!(Family::parse_list("d").unwrap(), [Family::D]);
        assert_eq!(Family::parse_list("a,b,c,d").unwrap(), [Family::A, Family::B, Family::C, Family::D]);
        assert_eq!(Family::parse_list("d,a").unwrap(), [Family::D, Family::A]);
        for bad in ["e", "", "a,,b", "a,a", "abcd", "all,d"] {
            assert!(Family::parse_list(bad).is_err(), "{bad}");
        }
        // a and b keep the seed streams they had before family c (0 and 2^32); d has its own.
        let streams = [Family::A, Family::B, Family::C, Family::D].map(Family::stream);
        assert_eq!(streams, [0, 1 << 32, 1 << 33, 3 << 32]);
    }

    #[test]
    fn allocation_meets_the_minimum_counts() {
        let k = kinds(200, 1);
        assert_eq!(k.len(), 200);
        assert!(k.iter().filter(|x| *x == "null").count() >= 56);
        for m in MECHANISMS {
            assert!(k.iter().filter(|x| *x == m).count() >= 14, "{m}");
        }
        for d in DECOYS {
            assert!(k.iter().filter(|x| *x == d).count() >= 8, "{d}");
        }
    }

    #[test]
    fn generator_invariants_on_a_few_datasets() {
        let p = Path::new("t.csv");
        for fam in [Family::A, Family::B, Family::C] {
            for (i, hidden) in ["null", "edge_ploughing", "size_effect", "decoy:gain"].iter().enumerate() {
                let d = dataset::generate(fam, i, hidden, 0, 11, None, material::NuisanceScope::Full).unwrap();
                // The CLI's readers accept both files.
                let tests = cutcal_io::tests_csv::parse_tests(p, &d.recordings).unwrap();
                let sims = cutcal_io::simulation_csv::parse_simulation(p, &d.simulation).unwrap();
                assert_eq!(tests.len(), sims.len());
                assert!((5..=30).contains(&tests.len()));
                let [with, without, sim] = &d.clean;
                let t = &d.truth;
                for (i, r) in rows(&d.recordings).iter().enumerate() {
                    let row: usize = r[0].parse::<usize>().unwrap() - 1;
                    let fc: f64 = r[5].parse::<f64>().unwrap() * 1e3;
                    // Recordings = noise-free truth up to the lognormal noise (5 sd).
                    assert!((fc / with[row][0]).ln().abs() < 5.0 * t.noise[0] + 0.01, "{hidden} row {i}");
                    let _ = i;
                }
                for (a, b) in without.iter().zip(sim) {
                    // Without the mechanism the truth differs from the nominal simulation only by the
                    // nuisance (eta, psi 3 %, thermal 5 %, JC 5 %): at most ~25 % on any output.
                    for o in 0..3 {
                        assert!((a[o] / b[o]).ln().abs() < 0.25, "{hidden} output {o}: {} vs {}", a[o], b[o]);
                    }
                }
                // A rival column can only lower what the nuisance leaves; the hidden mechanism is
                // never its own rival.
                if let (Some(chi2), Some(beyond)) = (t.rival_chi2, t.enr_beyond_nuisance) {
                    let count = (t.conditions * if t.columns.iter().any(|c| c == "t_int_c") { 4 } else { 3 }) as f64;
                    assert!(chi2 <= count * beyond * beyond * (1.0 + 1e-9) + 1e-12, "{hidden}: {chi2} vs {beyond}");
                    assert_ne!(t.nearest_rival.as_deref(), Some(*hidden));
                }
                assert_eq!(t.rival_chi2.is_some(), MECHANISMS.contains(hidden), "{hidden}");
                match *hidden {
                    "null" => {
                        assert!(with
                            .iter()
                            .zip(without)
                            .all(|(a, b)| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())));
                        assert!(t.enr.abs() < 1e-12);
                    }
                    "decoy:gain" => {
                        let g = t.strength.unwrap();
                        assert!(with
                            .iter()
                            .zip(without)
                            .all(|(a, b)| (a[0] / b[0] - g).abs() < 1e-9 && (a[2] - b[2]).abs() < 1e-15));
                    }
                    _ => {
                        // The ENR search lands on its target unless the physical bound stops it.
                        let target = t.target_enr.unwrap();
                        assert!(t.at_bound || (t.enr / target).ln().abs() < 0.1, "{hidden}: {} vs {target}", t.enr);
                    }
                }
                if *hidden == "edge_ploughing" {
                    // Ploughing only adds force: the chip thickness is unchanged, Fc and Ft grow.
                    for (a, b) in with.iter().zip(without) {
                        assert!(a[0] > b[0] && a[1] > b[1] && (a[2] - b[2]).abs() < 1e-15);
                    }
                }
            }
        }
    }
}
