//! Typed errors of the NURBS kernel.
//!
//! Every constructor of the kernel (`KnotVector::try_new`, `NurbsCurve::try_new`,
//! `NurbsSurface::try_new`, the builders) validates its input and reports what is wrong
//! with one of these variants. Part builders wrap them in their own error type.

use thiserror::Error;

/// What can be wrong with knots, control points or weights handed to the kernel.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum NurbsError {
    /// The degree is 0 or above [`MAX_DEGREE`](super::MAX_DEGREE).
    #[error("degree {degree} is out of range: expected 1..={max}")]
    DegreeOutOfRange {
        /// The degree that was asked for.
        degree: usize,
        /// The largest degree the kernel supports.
        max: usize,
    },
    /// A knot is NaN or infinite.
    #[error("knot {index} is {value}: knots must be finite")]
    KnotNotFinite {
        /// Position of the knot in the vector.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// Two consecutive knots decrease.
    #[error("knot {index} ({next}) is smaller than knot {} ({previous}): knots must not decrease", index - 1)]
    KnotsDecreasing {
        /// Position of the smaller knot.
        index: usize,
        /// The knot before it.
        previous: f64,
        /// The knot itself.
        next: f64,
    },
    /// The first or last knot does not repeat exactly `degree + 1` times.
    #[error(
        "knot vector is not clamped: the {end} knot appears {multiplicity} times, expected {expected}"
    )]
    NotClamped {
        /// `"first"` or `"last"`.
        end: &'static str,
        /// How many times it appears.
        multiplicity: usize,
        /// `degree + 1`.
        expected: usize,
    },
    /// An interior knot repeats more than `degree + 1` times.
    #[error("knot {knot} appears {multiplicity} times: at most degree + 1 = {max} allowed")]
    MultiplicityTooHigh {
        /// The repeated knot value.
        knot: f64,
        /// How many times it appears.
        multiplicity: usize,
        /// The largest multiplicity allowed.
        max: usize,
    },
    /// First and last knot are equal, so the parameter domain is empty.
    #[error("knot vector spans an empty domain [{start}, {end}]")]
    EmptyDomain {
        /// First knot.
        start: f64,
        /// Last knot.
        end: f64,
    },
    /// The number of control points does not match `knots − degree − 1`.
    #[error("{direction}: {got} control points given, the knot vector needs {expected}")]
    PointCountMismatch {
        /// `"curve"`, `"u"` or `"v"`.
        direction: &'static str,
        /// `knots − degree − 1`.
        expected: usize,
        /// Number of points given.
        got: usize,
    },
    /// A weight is zero, negative, NaN or infinite.
    #[error("weight {index} is {weight}: weights must be finite and > 0")]
    WeightNotPositive {
        /// Index of the control point (row-major for surfaces).
        index: usize,
        /// The weight.
        weight: f64,
    },
    /// A control-point coordinate is NaN or infinite.
    #[error("control point {index} has a non-finite coordinate")]
    PointNotFinite {
        /// Index of the control point (row-major for surfaces).
        index: usize,
    },
    /// A knot value to insert or split at lies outside the domain.
    #[error("parameter {value} lies outside the domain [{start}, {end}]")]
    ParameterOutOfDomain {
        /// The parameter.
        value: f64,
        /// Domain start.
        start: f64,
        /// Domain end.
        end: f64,
    },
    /// A geometric builder received an invalid number or an impossible combination.
    #[error("{what} is {value}: {rule}")]
    InvalidGeometry {
        /// The argument, e.g. `"radius"`.
        what: &'static str,
        /// Its value.
        value: f64,
        /// The rule it breaks, e.g. `"must be finite and > 0"`.
        rule: &'static str,
    },
    /// A Gauss–Legendre rule was asked for with 0 nodes or more than the kernel computes.
    #[error("Gauss–Legendre order {order} is out of range: expected 1..={max}")]
    QuadratureOrderOutOfRange {
        /// The number of nodes asked for.
        order: usize,
        /// The largest order supported.
        max: usize,
    },
    /// A point to project onto a curve or surface has a NaN or infinite coordinate.
    #[error("query point ({x}, {y}, {z}) has a non-finite coordinate")]
    QueryPointNotFinite {
        /// x coordinate.
        x: f64,
        /// y coordinate.
        y: f64,
        /// z coordinate.
        z: f64,
    },
    /// Knot insertion or refinement would repeat a knot more often than the degree.
    #[error(
        "inserting knot {knot} would give it multiplicity {multiplicity}: at most the degree {degree} allowed"
    )]
    InsertionExceedsDegree {
        /// The knot value being inserted.
        knot: f64,
        /// Its multiplicity after the insertion.
        multiplicity: usize,
        /// The degree, the largest multiplicity insertion may reach.
        degree: usize,
    },
    /// Knots handed to refinement are not in non-decreasing order.
    #[error("refinement knot {index} ({next}) is smaller than the one before ({previous})")]
    RefinementKnotsUnsorted {
        /// Position of the smaller knot in the slice given.
        index: usize,
        /// The knot before it.
        previous: f64,
        /// The knot itself.
        next: f64,
    },
    /// A parallel projection's direction lies (almost) in the target plane.
    #[error("projection direction is parallel to the plane (cosine to its normal {cosine})")]
    ProjectionParallelToPlane {
        /// Cosine of the angle between the unit direction and the unit plane normal.
        cosine: f64,
    },
    /// A straight generator of a neck-like surface does not meet the host surface
    /// (the nozzle does not touch its host there, or leaves the host patch).
    #[error(
        "the neck generator at u = {u} misses the host surface (closest approach {distance} mm)"
    )]
    GeneratorMissesHost {
        /// Neck parameter u of the generator.
        u: f64,
        /// Closest approach found between the generator and the host, mm.
        distance: f64,
    },
    /// Newton's iteration for a neck–host intersection point did not converge.
    #[error(
        "the intersection of the neck generator at u = {u} with the host did not converge (residual {residual} mm)"
    )]
    IntersectionNotConverged {
        /// Neck parameter u of the generator.
        u: f64,
        /// Distance between the neck and host points where the iteration stopped, mm.
        residual: f64,
    },
    /// A neck generator meets the host only beyond the ends of the neck.
    #[error(
        "the neck generator at u = {u} meets the host at v = {v}, outside the neck's v-domain [{start}, {end}]"
    )]
    IntersectionOutsideNeck {
        /// Neck parameter u of the generator.
        u: f64,
        /// Neck parameter v of the meeting point.
        v: f64,
        /// Start of the neck's v-domain.
        start: f64,
        /// End of the neck's v-domain.
        end: f64,
    },
    /// Following the intersection once around the neck did not return to its start.
    #[error("the neck–host intersection does not close after one turn of the neck: gap {gap} mm")]
    IntersectionNotClosed {
        /// Distance between the first point and the point reached after one turn, mm.
        gap: f64,
    },
    /// Sampling the intersection curve to the chordal tolerance needs too many points.
    #[error("sampling the intersection curve to {tolerance} mm needs more than {limit} points")]
    IntersectionTooManySamples {
        /// The chordal tolerance asked for, mm.
        tolerance: f64,
        /// The most samples allowed.
        limit: usize,
    },
}
