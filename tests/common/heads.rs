//! One head of every kind (and the notable presets) for a course of a given OD:
//! the list the head tests sweep.

use vesselcad::parts::heads::HeadKind;

/// Every head kind: hemispherical, 2:1 and a general ellipsoid, ASME F&D and
/// 80:10 torispherical, toriconical, pointed and truncated cones, flat with and
/// without a knuckle.
pub fn head_kinds(od: f64) -> Vec<HeadKind> {
    vec![
        HeadKind::Hemispherical,
        HeadKind::TWO_TO_ONE,
        HeadKind::Ellipsoidal { ratio: 1.7 },
        HeadKind::asme_fd(od),
        HeadKind::eighty_ten(od),
        HeadKind::Toriconical {
            half_angle: 30.0,
            knuckle_radius: 0.1 * od,
        },
        HeadKind::Conical {
            half_angle: 30.0,
            small_diameter: 0.0,
        },
        HeadKind::Conical {
            half_angle: 45.0,
            small_diameter: 0.25 * od,
        },
        HeadKind::Flat {
            knuckle_radius: 0.0,
        },
        HeadKind::Flat {
            knuckle_radius: 0.05 * od,
        },
    ]
}
