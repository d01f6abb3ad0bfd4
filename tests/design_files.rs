//! Design files as files: what `load` reads and what it refuses, before any
//! JSON is parsed — a byte-order mark, UTF-16 or broken UTF-8, a device such as
//! `/dev/zero` (which used to be read until memory ran out), a folder, a file
//! over the size limit — each refused with an error naming the file and why.

use std::path::{Path, PathBuf};

use vesselcad::design::{DesignError, MAX_DESIGN_BYTES, load};

fn example(name: &str) -> Vec<u8> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/designs")
        .join(name);
    std::fs::read(path).unwrap()
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

#[test]
fn a_byte_order_mark_is_skipped() {
    let dir = tempfile::tempdir().unwrap();
    let mut bytes = b"\xEF\xBB\xBF".to_vec();
    bytes.extend(example("horizontal-drum.json"));
    let path = write(dir.path(), "bom.json", &bytes);
    let design = load(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(design.vessels[0].tag, "V-101");
}

#[test]
fn utf16_and_broken_utf8_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "utf16.json", b"\xFF\xFE{\x00}\x00");
    let e = load(&path).unwrap_err().to_string();
    assert!(e.contains("UTF-16") && e.contains("utf16.json"), "{e}");

    let mut bytes = example("horizontal-drum.json");
    // A cut two-byte character on line 3.
    let at = bytes
        .iter()
        .enumerate()
        .filter(|(_, b)| **b == b'\n')
        .nth(1)
        .unwrap()
        .0
        + 3;
    bytes.insert(at, 0xC3);
    bytes.insert(at + 1, b'x');
    let path = write(dir.path(), "cut.json", &bytes);
    let e = load(&path).unwrap_err();
    assert!(matches!(e, DesignError::Syntax { .. }), "{e:?}");
    let e = e.to_string();
    assert!(
        e.contains("not UTF-8") && e.contains("0xC3") && e.contains("line 3 column 3"),
        "{e}"
    );
}

#[cfg(unix)]
#[test]
fn devices_and_folders_are_refused_before_reading() {
    let e = load("/dev/zero").unwrap_err();
    assert!(matches!(e, DesignError::Io { .. }), "{e:?}");
    assert!(e.to_string().contains("not a regular file"), "{e}");
    let dir = tempfile::tempdir().unwrap();
    let e = load(dir.path()).unwrap_err().to_string();
    assert!(e.contains("a folder"), "{e}");
}

#[test]
fn a_file_over_the_limit_is_refused_by_its_size() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("huge.json");
    let file = std::fs::File::create(&path).unwrap();
    // Sparse: no disk is used.
    file.set_len(MAX_DESIGN_BYTES + 1).unwrap();
    let e = load(&path).unwrap_err().to_string();
    assert!(
        e.contains(&format!("at most {MAX_DESIGN_BYTES} bytes")) && e.contains("huge.json"),
        "{e}"
    );
}

#[cfg(unix)]
#[test]
fn a_link_to_a_design_is_read_through() {
    let dir = tempfile::tempdir().unwrap();
    let target = write(dir.path(), "real.json", &example("storage-tank.json"));
    let link = dir.path().join("link.json");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    assert_eq!(load(&link).unwrap(), load(&target).unwrap());
}
