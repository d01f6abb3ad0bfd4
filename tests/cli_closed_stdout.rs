//! Every command whose standard output is a pipe nobody reads any more
//! (`vesselcad info plant.json | head -1`) ends quietly with status 0: no panic on
//! `EPIPE`, nothing on standard error.

mod common;

use std::process::{Command, Stdio};

/// Runs the binary with `args` and its standard output a pipe whose reading end
/// is already closed, so every write to it fails with `EPIPE`.
fn run_with_closed_stdout(args: &[&str]) -> std::process::Output {
    let (reader, writer) = std::io::pipe().expect("a pipe");
    drop(reader);
    Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args(args)
        .stdout(Stdio::from(writer))
        .stderr(Stdio::piped())
        .output()
        .expect("the binary runs")
}

#[test]
fn every_command_ends_quietly_when_its_reader_is_gone() {
    let design = common::examples::example_path("small-plant")
        .display()
        .to_string();
    let dir = tempfile::tempdir().unwrap();
    let file = |name: &str| dir.path().join(name).display().to_string();
    let (glb, svg, step, plant) = (
        file("plant.glb"),
        file("sheet.svg"),
        file("plant.step"),
        file("generated.json"),
    );
    let commands: Vec<Vec<&str>> = vec![
        vec!["info", &design],
        vec!["info", "--json", &design],
        vec!["check", &design],
        vec!["check", "--json", &design],
        vec!["build", &design, "-o", "-"],
        vec!["build", &design, "-o", &glb],
        vec!["drawing", &design, "--vessel", "V-101", "-o", "-"],
        vec!["drawing", &design, "--vessel", "V-101", "-o", &svg],
        vec!["export", &design, "-o", &step],
        vec!["plant", "generate", "--vessels", "2", "-o", &plant],
        vec!["simulate", &design, "--ticks", "1", "--edits-per-tick", "1"],
    ];
    for args in &commands {
        let o = run_with_closed_stdout(args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{args:?}: {stderr}");
        assert!(
            !stderr.contains("panicked") && !stderr.contains("Broken pipe"),
            "{args:?}: {stderr}"
        );
    }
}
