//! The bad-input catalogue (`fixtures/bad/`): every file through the real binary, with a non-zero
//! exit, no panic and the exact message pinned by a named snapshot.

use std::fs;

use super::{cutcal, root, stderr};

/// The files listed in `fixtures/bad/README.md` (`- \`name\`: what is wrong`).
fn listed() -> Vec<String> {
    let readme = fs::read_to_string(root().join("fixtures/bad/README.md")).expect("fixtures/bad/README.md");
    readme
        .lines()
        .filter_map(|l| l.strip_prefix("- `"))
        .filter_map(|l| l.split_once("`: "))
        .map(|(name, why)| {
            assert!(!why.trim().is_empty(), "fixtures/bad/README.md: `{name}` needs a line saying what is wrong");
            name.to_string()
        })
        .collect()
}

/// The command line that feeds `name` to `cutcal identify` beside a good C38 counterpart.
fn args(name: &str) -> Vec<String> {
    let bad = format!("fixtures/bad/{name}");
    let (material, tests) = if name.starts_with("tests_") {
        ("fixtures/materials/c38.toml".to_string(), bad)
    } else if name.starts_with("material_") {
        (bad, "fixtures/tests/c38.csv".to_string())
    } else if name.starts_with("jc_") {
        // A JC file goes through the forward model with the good C38 inputs.
        return [
            "predict",
            "--material",
            "fixtures/materials/c38.toml",
            "--jc",
            &bad,
            "--tests",
            "fixtures/tests/c38.csv",
        ]
        .map(String::from)
        .to_vec();
    } else if name.starts_with("simulation_") {
        // A simulation goes through Mode A's diagnosis against recordings of the same five cuts.
        return ["diagnose", "--recordings", "fixtures/diagnose/five_conditions_recordings.csv", "--simulation", &bad]
            .map(String::from)
            .to_vec();
    } else {
        panic!(
            "fixtures/bad/{name}: name it tests_*.csv, material_*.toml, jc_*.toml or simulation_*.csv so the catalogue knows how to run it"
        )
    };
    ["identify", "--material", &material, "--tests", &tests, "--starts", "4"].map(String::from).to_vec()
}

#[test]
fn readme_lists_every_bad_file_and_nothing_else() {
    let mut on_disk: Vec<String> = fs::read_dir(root().join("fixtures/bad"))
        .expect("fixtures/bad")
        .map(|e| e.expect("dir entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n != "README.md")
        .collect();
    on_disk.sort();
    let mut listed = listed();
    listed.sort();
    assert_eq!(on_disk, listed, "fixtures/bad/README.md must list every file there, one line each");
    // Issue 7 asks for a catalogue of at least 30 bad inputs.
    assert!(listed.len() >= 30, "only {} catalogue cases", listed.len());
}

#[test]
fn every_bad_input_fails_with_its_snapshot_message() {
    let root_text = root().to_string_lossy().into_owned();
    for name in listed() {
        let args = args(&name);
        let o = cutcal(&args.iter().map(String::as_str).collect::<Vec<_>>());
        let err = stderr(&o);
        assert!(!o.status.success(), "{name}: expected a non-zero exit, got success");
        assert_eq!(o.status.code(), Some(1), "{name}: expected exit code 1 (an error, not a crash): {err}");
        assert!(!err.contains("panicked"), "{name}: panicked: {err}");
        assert!(err.starts_with("error: "), "{name}: {err}");
        // Absolute paths differ between machines; the catalogue passes relative ones.
        let message = err.replace(&root_text, "[ROOT]");
        let snapshot = format!("catalogue__{}", name.replace('.', "_"));
        insta::with_settings!({ prepend_module_to_snapshot => false, omit_expression => true, description => format!("cutcal {}", args.join(" ")) }, {
            insta::assert_snapshot!(snapshot, message);
        });
    }
}
