//! The command line: `build` writes a valid GLB, `check` exits 0 for valid designs
//! and 1 with every problem listed for invalid ones, `info` reports figures, and
//! unreadable files exit 2. No input makes it panic.

mod common;

use std::process::Command;

fn vesselcad(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn example(name: &str) -> String {
    common::examples::example_path(name).display().to_string()
}

#[test]
fn build_writes_a_glb() {
    let dir = std::env::temp_dir().join(format!("vesselcad-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("drum.glb");
    let o = vesselcad(&[
        "build",
        &example("horizontal-drum"),
        "-o",
        out.to_str().unwrap(),
        "--tolerance",
        "1",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let bytes = std::fs::read(&out).unwrap();
    assert_eq!(&bytes[..4], b"glTF");
    let doc = gltf::Gltf::from_slice(&bytes).unwrap();
    assert!(doc.nodes().any(|n| n.name() == Some("V-101")));
    // Same design, same bytes.
    let again = dir.join("again.glb");
    assert!(
        vesselcad(&[
            "build",
            &example("horizontal-drum"),
            "-o",
            again.to_str().unwrap(),
            "--tolerance",
            "1"
        ])
        .status
        .success()
    );
    assert!(bytes == std::fs::read(&again).unwrap());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn levels_of_detail_without_tiles_are_refused_not_ignored() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("drum.glb");
    let o = vesselcad(&[
        "build",
        &example("horizontal-drum"),
        "-o",
        out.to_str().unwrap(),
        "--lod",
        "5,1",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("--lod") && stderr.contains("--tiles"),
        "{stderr}"
    );
    assert!(!out.exists(), "nothing is written");
}

#[test]
fn check_accepts_every_example() {
    for name in [
        "horizontal-drum",
        "vertical-column",
        "storage-tank",
        "small-plant",
    ] {
        let o = vesselcad(&["check", &example(name)]);
        assert!(
            o.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

#[test]
fn check_lists_every_problem_and_exits_1() {
    let dir = format!("{}/tests/bad_designs", env!("CARGO_MANIFEST_DIR"));
    let mut checked = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if !name.ends_with(".json") || name == "expected.json" || name.starts_with("control_") {
            continue;
        }
        let o = vesselcad(&["check", path.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{name}: {stderr}");
        assert!(stderr.starts_with("error: "), "{name}: {stderr}");
        assert!(!stderr.contains("panicked"), "{name}: {stderr}");
        checked += 1;
    }
    assert!(checked >= 30, "only {checked} bad designs");
}

#[test]
fn unreadable_files_and_bad_options_exit_2() {
    let o = vesselcad(&["check", "/nonexistent/design.json"]);
    assert_eq!(o.status.code(), Some(2));
    let o = vesselcad(&[
        "build",
        &example("horizontal-drum"),
        "-o",
        "/tmp/x.glb",
        "--tolerance",
        "-1",
    ]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(String::from_utf8_lossy(&o.stderr).contains("tolerance"));
    let o = vesselcad(&["frobnicate"]);
    assert_eq!(o.status.code(), Some(2));
}

/// A tolerance below what `f32` storage lets the mesher work to is one
/// options error before any meshing, from `check` and `build` alike (it was 33
/// mesh failures on the tank): it names the flag, the value, the design's
/// largest part and the smallest tolerance allowed. A vertex budget out of its
/// range is refused naming the flag and the value.
#[test]
fn mesh_options_the_design_cannot_take_are_one_error_naming_the_flag() {
    let tank = example("storage-tank");
    let glb = std::env::temp_dir().join(format!("vesselcad-floor-{}.glb", std::process::id()));
    let glb = glb.to_str().unwrap();
    for args in [vec!["check", &tank], vec!["build", &tank, "-o", glb]] {
        let o = vesselcad(&[&args[..], &["--tolerance", "0.000001"]].concat());
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "one error: {err}");
        for part in [
            "--tolerance 0.000001: ",
            "finer than f32 storage allows for this design",
            "its largest part reaches 9000 mm",
            "the smallest tolerance is 2e-6 mm",
        ] {
            assert!(err.contains(part), "{args:?}: {part:?} not in {err}");
        }
    }
    assert!(!std::path::Path::new(glb).exists());
    let o = vesselcad(&["check", &tank, "--json", "--tolerance", "0.000001"]);
    assert_eq!(o.status.code(), Some(2));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["kind"], "options", "{v}");
    assert!(v.get("failures").is_none(), "{v}");
    for n in ["999", "0", "4294967296", "many"] {
        let o = vesselcad(&["check", &tank, "--max-vertices", n]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{n}: {err}");
        assert!(
            err.contains("--max-vertices") && err.contains(n),
            "{n}: {err}"
        );
    }
}

#[test]
fn info_reports_figures() {
    let o = vesselcad(&["info", &example("vertical-column"), "--json"]);
    assert!(o.status.success());
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["format"], "vesselcad-info/1");
    assert_eq!(v["units"]["length"], "mm");
    assert_eq!(v["units"]["volume"], "m3");
    let c = &v["vessels"][0];
    assert_eq!(c["tag"], "C-201");
    assert_eq!(c["tangent_length"], 21000.0);
    assert_eq!(c["outside_diameter"], 2000.0);
    assert_eq!(c["nozzles"].as_array().unwrap().len(), 10);
    // Volume: courses, reducer frustum and two heads (2:1 bottom, F&D top) with
    // their straight flanges, from closed forms.
    let pi = std::f64::consts::PI;
    let courses = pi * 1.0f64.powi(2) * 12.0 + pi * 0.7f64.powi(2) * 8.0;
    let frustum = pi * 0.9 / 3.0 * (1.0 + 0.7 + 0.49);
    let two_to_one = pi * 2.0f64.powi(3) / 24.0 + pi * 0.05;
    let volume = c["volume"].as_f64().unwrap();
    assert!(
        volume > courses + frustum + two_to_one && volume < courses + frustum + two_to_one + 0.6,
        "{volume}"
    );
    let o = vesselcad(&["info", &example("horizontal-drum")]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("V-101 (horizontal)"));
}

#[test]
fn inch_designs_load_as_millimetres() {
    let text = std::fs::read_to_string(example("horizontal-drum")).unwrap();
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    json["units"] = "in".into();
    let v = &mut json["vessels"][0];
    v["parts"][1]["shell"]["od"] = 100.0.into();
    v["parts"][1]["shell"]["length"] = 300.0.into();
    let design = vesselcad::design::parse_unchecked(&json.to_string()).unwrap();
    let mut d = design.clone();
    vesselcad::design::units::to_millimetres(&mut d);
    let vesselcad::design::PartDesign::Shell(s) = &d.vessels[0].parts[1] else {
        panic!()
    };
    assert_eq!((s.od, s.length), (2540.0, 7620.0));
    assert_eq!(d.units, vesselcad::design::Units::Mm);
    assert_eq!(
        d.vessels[0].nozzles[0].size, 8.0,
        "NPS is a name, never scaled"
    );
}

#[test]
fn dash_writes_to_standard_output_and_gltf_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .current_dir(dir.path())
        .args([
            "build",
            &example("horizontal-drum"),
            "-o",
            "-",
            "--tolerance",
            "5",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(&o.stdout[..4], b"glTF");
    gltf::Gltf::from_slice(&o.stdout).unwrap();
    assert!(String::from_utf8_lossy(&o.stderr).contains("<stdout>"));
    assert!(!dir.path().join("-").exists(), "wrote a file named -");

    let o = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .current_dir(dir.path())
        .args(["drawing", &example("horizontal-drum"), "--vessel", "V-101"])
        .args(["-o", "-", "--tolerance", "5"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(o.stdout.starts_with(b"<svg"));
    assert!(!dir.path().join("-").exists(), "wrote a file named -");

    let gltf = dir.path().join("x.gltf");
    let o = vesselcad(&[
        "build",
        &example("horizontal-drum"),
        "-o",
        gltf.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains(".glb"));
    assert!(!gltf.exists());
}

#[test]
fn check_json_names_its_format_and_every_problem() {
    let o = vesselcad(&["check", &example("storage-tank"), "--json"]);
    assert_eq!(o.status.code(), Some(0));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["format"], "vesselcad-check/1");
    assert_eq!(v["valid"], true);
    assert_eq!(v["vessels"], 1);

    let bad = format!(
        "{}/tests/bad_designs/inch_file_negative_length.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let o = vesselcad(&["check", &bad, "--json"]);
    assert_eq!(o.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(
        (v["valid"].clone(), v["kind"].clone()),
        (false.into(), "invalid".into())
    );
    let violation = &v["violations"][0];
    assert_eq!(violation["path"], "vessels[0].parts[1].shell.length");
    assert_eq!(violation["value"], "-1 in (= -25.4 mm)");

    let o = vesselcad(&["check", "/nonexistent/design.json", "--json"]);
    assert_eq!(o.status.code(), Some(2));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["kind"], "unreadable");

    // Two designs in one file are not one design.
    let two = format!(
        "{}/tests/bad_designs/syntax_two_designs_concatenated.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let o = vesselcad(&["check", &two]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("after the design's JSON object"));
}

/// A design that passes every rule but cannot be built is not valid to `check`,
/// and `build` refuses it; both report what failed as a build failure, not as a
/// broken rule: the part's design path, its stable id, the stage and patch that
/// failed and the mesher's typed cause. The design is `common::unbuildable`'s:
/// head H2 of the horizontal drum made hemispherical, under a vertex budget its
/// crown then needs more than (and the example within it builds).
#[test]
fn check_and_build_report_what_cannot_be_built_by_design_path() {
    use common::unbuildable::{
        ENTITY, PATCH, PATH, TOLERANCE, buildable_json, option_args, unbuildable_json, written,
    };
    let options = option_args();
    let with = |args: &[&str]| {
        let mut all: Vec<&str> = args.to_vec();
        all.extend(options.iter().map(String::as_str));
        vesselcad(&all)
    };
    let (_dir, example) = written(&buildable_json());
    let o = with(&["check", example.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (_dir, edited) = written(&unbuildable_json());
    let edited = edited.to_str().unwrap();
    let o = with(&["check", edited, "--json"]);
    assert_eq!(o.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(
        (v["valid"].clone(), v["kind"].clone()),
        (false.into(), "geometry".into()),
        "{v}"
    );
    assert!(v.get("violations").is_none(), "not a rule: {v}");
    let f = &v["failures"][0];
    assert_eq!(f["path"], PATH, "{v}");
    assert_eq!(f["entity"], ENTITY, "{v}");
    assert_eq!(
        (f["stage"].clone(), f["patch"].clone()),
        ("mesh".into(), PATCH.into()),
        "{v}"
    );
    assert!(f["cause"].as_str().unwrap().contains("max_vertices"), "{v}");
    // Text: one line per failure, by design path.
    let o = with(&["check", edited]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains(&format!(
            "every rule holds, but the geometry cannot be built at {TOLERANCE} mm"
        )),
        "{err}"
    );
    let line = format!("{PATH}: {ENTITY}: its patch \"{PATCH}\" cannot be meshed");
    assert!(err.contains(&line), "{err}");
    // The rules alone hold.
    assert!(
        vesselcad(&["check", edited, "--rules-only"])
            .status
            .success()
    );
    let glb =
        std::env::temp_dir().join(format!("vesselcad-unbuildable-{}.glb", std::process::id()));
    let o = with(&["build", edited, "-o", glb.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains(&format!("error: {line}")), "{err}");
    assert!(!glb.exists());
}
