//! Scratch: mesh a hemisphere R 1000 and an F&D head at 0.1 mm repeatedly (profiling).
use std::time::Instant;
use vesselcad::mesh::cdt::{mesh_patch_region, mesh_region};
use vesselcad::mesh::{TessellationOptions, patch_region};
use vesselcad::parts::heads::{Head, HeadKind};

fn main() {
    let reps: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(5);
    let tol: f64 = std::env::args()
        .nth(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.1);
    let options = TessellationOptions::chord(tol);
    let hemi = Head::new(2000.0, HeadKind::Hemispherical)
        .patches()
        .unwrap();
    let fd = Head::new(2400.0, HeadKind::asme_fd(2400.0))
        .patches()
        .unwrap();
    for (name, patches) in [("hemisphere", &hemi), ("fd", &fd)] {
        let mut best = f64::INFINITY;
        let mut tris = 0;
        for _ in 0..reps {
            let t = Instant::now();
            tris = 0;
            for p in patches.iter() {
                let region = patch_region(&p.surface, &options, &[], None).unwrap();
                let (m, st) = if std::env::var("GN").is_ok() {
                    mesh_region(&p.surface, &region, &options).unwrap()
                } else {
                    mesh_patch_region(p, &region, &options).unwrap()
                };
                tris += m.triangle_count();
                if std::env::var("STATS").is_ok() {
                    eprintln!("{:?} verts {}", st, m.positions.len());
                }
            }
            best = best.min(t.elapsed().as_secs_f64());
        }
        println!(
            "{name}: {tris} triangles, best {:.1} ms, {:.0} ns/triangle",
            best * 1e3,
            best * 1e9 / tris as f64
        );
    }
}
