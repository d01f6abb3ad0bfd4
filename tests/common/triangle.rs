//! The largest distance from a flat triangle to an analytic surface, found
//! independently of the mesher's own estimate (`mesh::cdt::peak`): the best of
//! 45 barycentric samples (the 8th subdivision of the sides), then a pattern
//! search in barycentric coordinates (six directions, the step halved when none
//! climbs) down to a step of 1e-6.

use glam::DVec3;
use vesselcad::parts::Analytic;

/// Distance from the point of barycentric coordinates `l` of `p` to the surface.
pub fn distance_at(analytic: &Analytic, p: [DVec3; 3], l: [f64; 3]) -> f64 {
    analytic.distance(p[0] * l[0] + p[1] * l[1] + p[2] * l[2])
}

/// The largest distance from triangle `p` to `analytic` (see the module doc).
pub fn largest_distance(analytic: &Analytic, p: [DVec3; 3]) -> f64 {
    const N: usize = 8;
    const DIRECTIONS: [[f64; 3]; 6] = [
        [1.0, -1.0, 0.0],
        [-1.0, 1.0, 0.0],
        [0.0, 1.0, -1.0],
        [0.0, -1.0, 1.0],
        [-1.0, 0.0, 1.0],
        [1.0, 0.0, -1.0],
    ];
    let mut best = (f64::NEG_INFINITY, [0.0; 3]);
    for i in 0..=N {
        for j in 0..=N - i {
            let l = [i, j, N - i - j].map(|x| x as f64 / N as f64);
            let d = distance_at(analytic, p, l);
            if d > best.0 {
                best = (d, l);
            }
        }
    }
    let mut step = 0.5 / N as f64;
    while step > 1e-6 {
        let mut moved = false;
        for d in DIRECTIONS {
            let l = [0, 1, 2].map(|k| best.1[k] + step * d[k]);
            if l.iter().any(|&x| x < 0.0) {
                continue;
            }
            let value = distance_at(analytic, p, l);
            if value > best.0 {
                best = (value, l);
                moved = true;
            }
        }
        if !moved {
            step *= 0.5;
        }
    }
    best.0
}
