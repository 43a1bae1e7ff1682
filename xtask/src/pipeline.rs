//! `cargo xtask pipeline`: a thin driver over `cutcal run` for every project in
//! `fixtures/projects/`, writing `target/pipeline/<project>/` and one summary table.

use std::fs;

use anyhow::{bail, Context, Result};

use cutcal_io::output::StagedDir;

use crate::flags::PipelineFlags;

/// Runs every project file (sorted by name) and prints a summary.
pub fn run(flags: &PipelineFlags) -> Result<()> {
    let mut projects: Vec<_> = fs::read_dir(&flags.projects)
        .with_context(|| format!("cannot read the projects directory {}", flags.projects.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    projects.sort();
    if projects.is_empty() {
        bail!("{}: no project files (*.toml)", flags.projects.display());
    }
    // The whole output root is staged: a failure in any project leaves the previous outputs (or
    // nothing) in place, never a half-written tree.
    let staged = StagedDir::new(&flags.out)?;
    let mut summary = Vec::new();
    let bar = cutcal_cli::progress::bar(projects.len() as u64, "pipeline projects", flags.quiet);
    for p in &projects {
        let project = cutcal_report::project::load_project(p)?;
        let out = staged.path(&project.name);
        let progress = cutcal_cli::progress::Terminal::new(flags.quiet);
        let report = cutcal_report::stages::run_project(p, &out, &progress)
            .with_context(|| format!("project {}", p.display()))?;
        summary.push(report);
        bar.inc(1);
    }
    bar.finish_and_clear();
    staged.commit()?;
    if flags.json {
        println!("{}", serde_json::to_string_pretty(&summary)?);
        return Ok(());
    }
    println!(
        "{:<10} {:<10} {:>9} {:>9} {:>7} {:>8} {:>6} {:>7} {:>6}",
        "project", "model", "A [MPa]", "B [MPa]", "n", "C", "m", "RMS", "files"
    );
    for r in &summary {
        if r.identification.is_empty() {
            println!(
                "{:<10} {:<10} {:>9} {:>9} {:>7} {:>8} {:>6} {:>7} {:>6}",
                r.project,
                "-",
                "-",
                "-",
                "-",
                "-",
                "-",
                "-",
                r.files.len()
            );
        }
        for (k, i) in &r.identification {
            println!(
                "{:<10} {:<10} {:>9.1} {:>9.1} {:>7.3} {:>8.4} {:>6.3} {:>7.1} {:>6}",
                r.project,
                k,
                i.jc.a_mpa,
                i.jc.b_mpa,
                i.jc.n,
                i.jc.c,
                i.jc.m,
                i.rms_mpa,
                r.files.len()
            );
        }
    }
    println!("outputs in {}/<project>/", flags.out.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::{Path, PathBuf};

    use super::*;

    fn flags(out: &Path, projects: &Path) -> PipelineFlags {
        PipelineFlags { out: out.to_path_buf(), projects: projects.to_path_buf(), quiet: true, json: true }
    }

    fn root() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
    }

    fn all_files(dir: &Path) -> Vec<PathBuf> {
        let mut v = Vec::new();
        for e in fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                v.extend(all_files(&p));
            } else {
                v.push(p);
            }
        }
        v.sort();
        v
    }

    /// Checks that an SVG is well-formed XML and names its data series.
    fn svg_series(path: &Path) -> Vec<String> {
        let text = fs::read_to_string(path).unwrap();
        let mut reader = quick_xml::Reader::from_str(&text);
        let mut names = Vec::new();
        let mut depth = 0i32;
        loop {
            match reader.read_event() {
                Ok(quick_xml::events::Event::Start(e)) => {
                    depth += 1;
                    if let Some(a) = e.try_get_attribute("data-name").unwrap() {
                        names.push(String::from_utf8_lossy(&a.value).into_owned());
                    }
                }
                Ok(quick_xml::events::Event::End(_)) => depth -= 1,
                Ok(quick_xml::events::Event::Eof) => break,
                Ok(_) => {}
                Err(e) => panic!("{}: not well-formed: {e}", path.display()),
            }
        }
        assert_eq!(depth, 0, "{}: unbalanced", path.display());
        names
    }

    #[test]
    fn pipeline_writes_parseable_outputs_and_is_byte_identical() {
        let tmp = tempfile::tempdir().unwrap();
        let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
        run(&flags(&a, &root().join("fixtures/projects"))).unwrap();
        run(&flags(&b, &root().join("fixtures/projects"))).unwrap();
        let fa = all_files(&a);
        assert_eq!(fa.len(), all_files(&b).len());
        for f in &fa {
            let rel = f.strip_prefix(&a).unwrap();
            assert_eq!(fs::read(f).unwrap(), fs::read(b.join(rel)).unwrap(), "{} differs between runs", rel.display());
        }
        for project in ["c38", "42crmo4", "aa6082", "aisi1045", "c38_signals"] {
            let dir = a.join(project);
            let report: serde_json::Value =
                serde_json::from_slice(&fs::read(dir.join("report.json")).unwrap()).unwrap();
            for f in report["files"].as_array().unwrap() {
                assert!(dir.join(f.as_str().unwrap()).is_file(), "{project}: {f} listed but missing");
            }
            assert!(fs::read_to_string(dir.join("report.md")).unwrap().starts_with("# cutcal report"));
        }
        // The paper's Fig 4 analogue carries both models.
        assert_eq!(svg_series(&a.join("c38/fig4_temperature.svg")), vec!["original DPZD", "enhanced DPZD"]);
        for f in fa.iter().filter(|f| f.extension().is_some_and(|e| e == "svg")) {
            assert!(!svg_series(f).is_empty(), "{}: no series", f.display());
        }
        // The plot shown in the README is the generated one (run `cargo xtask pipeline` and copy
        // target/pipeline/c38/fig4_temperature.svg to docs/img/ when this fails).
        assert_eq!(
            fs::read(a.join("c38/fig4_temperature.svg")).unwrap(),
            fs::read(root().join("docs/img/fig4_temperature.svg")).unwrap(),
            "docs/img/fig4_temperature.svg is stale"
        );
        // The pipeline's own cards pass the exporter's validators: dynars reads the LS-DYNA deck back
        // with the identified A (report.json), and the MatML document is well-formed XML.
        for project in ["c38", "42crmo4", "aa6082", "c38_signals"] {
            let deck = a.join(format!("{project}/cards/{}_lsdyna.k", project.trim_end_matches("_signals")));
            let parsed = dynars::deck::parse_deck(&deck).unwrap_or_else(|e| panic!("{}: {e}", deck.display()));
            let file = parsed.files().next().unwrap();
            let jc = file.keywords().find(|k| k.base() == "MAT_JOHNSON_COOK").expect("MAT_JOHNSON_COOK parsed");
            let a_mpa = jc.field("A").and_then(|f| f.as_f64()).expect("A read back");
            let report: serde_json::Value =
                serde_json::from_slice(&fs::read(a.join(format!("{project}/report.json"))).unwrap()).unwrap();
            let want = report["jc_used"][1]["a_mpa"].as_f64().unwrap();
            assert!((a_mpa - want).abs() <= 1e-5 * want, "{project}: deck A {a_mpa} vs report {want}");
            let matml = a.join(format!("{project}/cards/{}_matml.xml", project.trim_end_matches("_signals")));
            let _ = svg_series(&matml); // well-formed (the helper panics otherwise)
        }
        // No output carries a NaN or an infinity (issue 13): a missing number is "not available"
        // with its reason. serde_json writes non-finite floats as null, Rust's formatting as
        // `NaN`/`inf`, so the text is scanned for those tokens.
        for f in &fa {
            let text = fs::read_to_string(f).unwrap_or_default();
            for tok in text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')) {
                let t = tok.to_ascii_lowercase();
                assert!(!matches!(t.as_str(), "nan" | "inf" | "infinity"), "{}: contains `{tok}`", f.display());
            }
        }
        // A skipped DPZD identification says why (AISI 1045: no chip thickness column).
        let md = fs::read_to_string(a.join("aisi1045/report.md")).unwrap();
        assert!(md.contains("Not run: the DPZD identification (paper Eq 15) needs the measured Fc, Ft and tc of one test, and aisi1045.csv has no tc column"), "{md}");
        // The signals project: signals -> rows -> identification -> cards -> diagnosis. The rows
        // hold the reduced means: the SYNTHETIC signals are built at Table 6's 224 and 186 N/mm.
        let s: serde_json::Value =
            serde_json::from_slice(&fs::read(a.join("c38_signals/report.json")).unwrap()).unwrap();
        let rec = s["recordings"].as_array().unwrap();
        assert_eq!(rec.iter().filter(|r| r["analysis"].is_object()).count(), 3);
        let rows = cutcal_io::tests_csv::load_tests(&a.join("c38_signals/measured_tests.csv")).unwrap();
        let t3 = rows.iter().find(|t| t.id == "3").unwrap();
        for (got, want) in [(t3.measured.cutting_force_n_per_m, 224e3), (t3.measured.feed_force_n_per_m, 186e3)] {
            assert!((got.unwrap() / want - 1.0).abs() < 0.005, "{got:?} vs {want}");
        }
        assert!(t3.measured.sd.cutting_force_n_per_m.is_some());
        assert!(s["identification"]["enhanced"]["jc"]["a_mpa"].as_f64().is_some());
        assert!(a.join("c38_signals/cards/c38_abaqus_jc.inp").is_file());
        assert!(s["diagnosis"]["report"].is_object(), "the signals project runs the diagnosis");
        assert!(fs::read_to_string(a.join("c38_signals/report.md")).unwrap().contains("## Diagnosis"));
        // C38 identification in the report: Table 4 original A within 2 % (paper: 671 MPa).
        let r: serde_json::Value = serde_json::from_slice(&fs::read(a.join("c38/report.json")).unwrap()).unwrap();
        let a_orig = r["identification"]["original"]["jc"]["a_mpa"].as_f64().unwrap();
        assert!((a_orig - 671.0).abs() < 0.02 * 671.0, "{a_orig}");
    }

    #[test]
    fn broken_fixture_stops_with_a_located_error_and_leaves_nothing() {
        let tmp = tempfile::tempdir().unwrap();
        let projects = tmp.path().join("projects");
        fs::create_dir_all(&projects).unwrap();
        let text = fs::read_to_string(root().join("fixtures/projects/c38.toml")).unwrap();
        let fixtures = root().join("fixtures").canonicalize().unwrap();
        let text = text.replace("../", &format!("{}/", fixtures.display()));
        fs::write(projects.join("a_good.toml"), &text).unwrap();
        let broken_tests = tmp.path().join("broken.csv");
        fs::write(&broken_tests, "test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n_per_mm,ft_n_per_mm,chip_mm\n3,240,0.075,1.95,0,224,abc,0.157\n").unwrap();
        let bad = text
            .replace(&format!("{}/tests/c38.csv", fixtures.display()), broken_tests.to_str().unwrap())
            .replace("name = \"c38\"", "name = \"z_bad\"");
        fs::write(projects.join("z_bad.toml"), bad).unwrap();
        let out = tmp.path().join("out");
        let err = format!("{:#}", run(&flags(&out, &projects)).unwrap_err());
        assert!(err.contains("broken.csv:2: field `ft_n_per_mm` = 'abc'"), "{err}");
        assert!(!out.exists(), "a failed pipeline must not leave an output directory");
        // Only the two inputs remain: no output, no staging directory.
        assert_eq!(fs::read_dir(tmp.path()).unwrap().count(), 2, "staging left behind");
        // A wrong projects path is a located error too.
        let err = format!("{:#}", run(&flags(&out, &tmp.path().join("nope"))).unwrap_err());
        assert!(err.contains("nope"), "{err}");
    }
}
