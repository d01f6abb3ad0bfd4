//! The fitted (as-built) surfaces as STEP, read back by OpenCASCADE: the file
//! reads without failure, every shape and face is valid, each fitted patch is
//! one face named `<tag> as-built/<part>/<patch>`, and OCCT's points of each
//! face's surface lie on vesselcad's fitted NURBS (placed in the plant) to
//! 1e-9 × the vessel's size — the fit's surface, not the design's, which a
//! dented patch leaves by millimetres.

mod common;

use common::occt::{occt_python, occt_report};
use common::scan::{TORI_ECCENTRIC, envelope};
use glam::DVec3;
use vesselcad::scan::defects::parse_defects;
use vesselcad::scan::fit::FitOptions;
use vesselcad::scan::inspect::{InspectOptions, inspect};
use vesselcad::scan::simulate::{SimulateOptions, simulate};
use vesselcad::scan::step::fitted_step;

#[test]
fn occt_reads_the_fitted_surfaces_valid_and_on_our_evaluation() {
    let Some(python) = occt_python() else {
        return;
    };
    // Torispherical head (flange, knuckle, crown with its pole), courses, an
    // eccentric cone (a ruled surface), an ellipsoidal head; a dent on S1.
    let env = envelope(TORI_ECCENTRIC);
    let points = simulate(
        &env,
        &SimulateOptions {
            density: 150.0,
            noise: 1.0,
            occlusion: 0.0,
            seed: 41,
            site: None,
            defects: parse_defects("dent=20mm@EL1500/45°", &env).unwrap(),
        },
    )
    .unwrap()
    .points;
    let options = InspectOptions {
        register: None,
        fit: FitOptions {
            noise: 1.0,
            ..FitOptions::DEFAULT
        },
        ..InspectOptions::DEFAULT
    };
    let inspection = inspect(&env, points, &options).unwrap();
    let text = fitted_step(&env, &inspection.fits, "as-built.step").unwrap();
    let report = occt_report(&python, &text, "scan-as-built.step", 4);
    assert_eq!(report["read"], true);
    assert_eq!(report["read_failures"], 0);
    assert_eq!(report["valid"], true);
    let mut products: Vec<&str> = report["products"]
        .as_array()
        .expect("products")
        .iter()
        .map(|p| p.as_str().expect("name"))
        .collect();
    products.sort_unstable();
    assert_eq!(products, ["V-3 as-built", "plant"]);

    // Ours: every fitted envelope patch, by name.
    let ours: Vec<(String, usize)> = env
        .surfaces
        .iter()
        .enumerate()
        .filter(|(i, s)| env.parts[s.part].role.is_envelope() && inspection.fits[*i].is_some())
        .map(|(i, s)| {
            (
                format!("V-3 as-built/{}/{}", env.parts[s.part].id, s.patch.name),
                i,
            )
        })
        .collect();
    // H1's flange, knuckle and crown, S1, R1, S2, H2's flange and crown.
    assert_eq!(ours.len(), 8, "{ours:?}");
    let faces = report["face_list"].as_array().expect("faces");
    assert_eq!(faces.len(), ours.len(), "{faces:#?}");
    let size = 6000.0;
    let mut off_design: f64 = 0.0;
    for f in faces {
        let name = f["name"].as_str().expect("face name");
        assert_eq!(f["valid"], true, "{name}");
        let &(_, i) = ours
            .iter()
            .find(|(n, _)| n == name)
            .unwrap_or_else(|| panic!("{name} is not a fitted patch"));
        let s = &env.surfaces[i];
        let fitted = &inspection.fits[i].as_ref().unwrap().surface;
        let place = env.frame * s.frame;
        for p in f["points"].as_array().expect("points") {
            let p: Vec<f64> = p
                .as_array()
                .expect("point")
                .iter()
                .map(|x| x.as_f64().expect("number"))
                .collect();
            let theirs = DVec3::new(p[2], p[3], p[4]);
            let ours = place.transform_point3(fitted.point(p[0], p[1]));
            assert!(
                ours.distance(theirs) <= 1e-9 * size,
                "{name} at ({}, {}): {ours} vs {theirs}",
                p[0],
                p[1]
            );
            let design = place.transform_point3(s.patch.surface.point(p[0], p[1]));
            off_design = off_design.max(design.distance(theirs));
        }
    }
    // The file holds the fit: somewhere its surface leaves the design's by
    // more than the noise averages out to.
    assert!(off_design > 0.05, "{off_design}");
}
