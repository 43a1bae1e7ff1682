//! A reader that closes the pipe early (`cutcal ... | head`): the binary ends quietly with success,
//! never with a panic in the print (`cutcal_cli::output`).

use std::process::{Command, Stdio};

use super::root;

#[test]
fn a_closed_stdout_pipe_ends_quietly_with_success() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_cutcal"))
        .args([
            "diagnose",
            "--recordings",
            "fixtures/diagnose/five_conditions_recordings.csv",
            "--simulation",
            "fixtures/diagnose/five_conditions_simulation.csv",
            "--json",
        ])
        .current_dir(root())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run cutcal");
    // Close the read end before the diagnosis (a few hundred ms) has printed anything.
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("wait for cutcal");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "status {:?}: {err}", out.status);
    assert!(!err.contains("panicked"), "{err}");
}
