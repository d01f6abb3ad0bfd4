use std::time::Instant;
use vesselcad::design::{PartDesign, load};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model, Views};
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let delta: f64 = std::env::args()
        .nth(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(-100.0);
    let design = load(std::path::Path::new(&path)).unwrap();
    let mut model =
        Model::from_design_with(&design, TessellationOptions::chord(1.0), Views::Off).unwrap();
    let v = &design.vessels[0];
    for round in 0..4 {
        let mut part = v.parts.iter().find(|p| p.id() == "S1").unwrap().clone();
        if let PartDesign::Shell(s) = &mut part {
            s.length += if round % 2 == 0 { delta } else { 0.0 };
        }
        model
            .apply(Edit::SetPart {
                vessel: v.tag.clone(),
                part,
            })
            .unwrap();
        let t = Instant::now();
        let c = model.update();
        println!(
            "round {round}: {:.2} ms, meshes {} tris {} cuts {} placed {}",
            t.elapsed().as_secs_f64() * 1e3,
            c.meshes_rebuilt,
            c.triangles_meshed,
            c.openings_cut,
            c.openings_placed
        );
    }
}
