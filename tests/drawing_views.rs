//! Drawing views: exact silhouettes, hidden-line classification and the
//! incremental Project stage (work counters, equality with a fresh build).

use std::time::Instant;

use vesselcad::design::{Design, NozzleDesign, parse};
use vesselcad::drawing::vessel_views;
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};
use vesselcad::project::{LineKind, View, ViewKind};

fn example(name: &str) -> Design {
    let path = format!("{}/examples/designs/{name}.json", env!("CARGO_MANIFEST_DIR"));
    vesselcad::design::load(std::path::Path::new(&path)).expect("example loads")
}

fn options() -> TessellationOptions {
    TessellationOptions::chord(0.5)
}

#[test]
fn explore_column() {
    let t = Instant::now();
    let m = Model::from_design(&example("vertical-column"), options()).unwrap();
    eprintln!("build {:?}", t.elapsed());
    let views = vessel_views(&m, "C-201").unwrap();
    for v in &views {
        let n: usize = v.entities.iter().map(|e| e.lines.len()).sum();
        let h: usize = v.entities.iter().flat_map(|e| &e.lines).filter(|l| l.kind == LineKind::Hidden).count();
        eprintln!("{:?}: {} entities, {n} lines, {h} hidden, bounds {:?}", v.projection.kind, v.entities.len(), v.bounds());
    }
}
