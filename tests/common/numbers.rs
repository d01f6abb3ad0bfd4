//! Numbers a user could type or a file could hold, weighted towards trouble: the
//! inputs of the never-panic property tests.

use proptest::prelude::*;

/// Any f64, with the special values, lengths up to `length` mm and angles up to
/// `angle` degrees over-represented.
pub fn any_number_up_to(length: f64, angle: f64) -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(f64::MIN_POSITIVE),
        Just(f64::MAX),
        Just(1e-300),
        Just(1e300),
        -1e4..1e4f64,
        0.0..length,
        0.0..angle,
        proptest::num::f64::ANY,
    ]
}
