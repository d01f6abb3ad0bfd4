//! Why an opening cannot be cut: [`CutError`], one variant per way the cut
//! stage fails, each carrying the host patch, the loop and the coordinate or
//! kernel failure it met, with wording that says what to change in the design.
//! The Geometry stage reports it against the nozzle (or boot) whose opening it
//! is, by design path (`systems::cut_openings`).

use thiserror::Error;

use crate::nurbs::NurbsError;

/// Which of an opening's loops a failure met.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CutLoop {
    /// Where the nozzle's neck (a boot's shell) meets the host.
    Neck,
    /// Where the reinforcing pad's outside edge meets the host.
    Pad,
}

impl std::fmt::Display for CutLoop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            CutLoop::Neck => "the neck's loop",
            CutLoop::Pad => "the reinforcing pad's outer loop",
        })
    }
}

/// A failure of cutting one opening in its host part.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum CutError {
    /// The host part has no patch to cut (it was not built).
    #[error("the host has no patch to cut")]
    NoHostPatch,
    /// The neck or pad could not be moved into the host part's frame (a
    /// degenerate placement).
    #[error("cannot place the nozzle in its host's frame: {0}")]
    Placement(NurbsError),
    /// An exact surface the cut builds could not be made: the pad's outside
    /// cylinder or a straight course's canonical copy.
    #[error("cannot build {what}: {source}")]
    Construction {
        /// What was being built.
        what: &'static str,
        /// The kernel's reason.
        source: NurbsError,
    },
    /// A cut kept from a straight course was placed on a host patch that is
    /// not one (the cut stage holds kept cuts to their course, so this is a
    /// defect of the stage, not of the design).
    #[error("host patch {patch:?} is not a straight course, yet a course's cut was placed on it")]
    NotACourse {
        /// The host patch.
        patch: &'static str,
    },
    /// A loop could not be marched on a host patch: the neck (or pad) misses
    /// the patch, runs off it, or the march did not converge or close.
    #[error("{which} on host patch {patch:?}: {source}")]
    Intersection {
        /// The loop.
        which: CutLoop,
        /// The host patch.
        patch: &'static str,
        /// The kernel's reason.
        source: NurbsError,
    },
    /// A loop marched on a straight course leaves the course at an end.
    #[error(
        "{which} runs past an end of the course {patch:?} (it reaches z = {z:.3} mm of \
         the course's {z0:.3}..{z1:.3} mm); move the nozzle away from the course's end \
         or make the course longer"
    )]
    PastCourseEnd {
        /// The loop.
        which: CutLoop,
        /// The course's patch.
        patch: &'static str,
        /// The axial position the loop reaches, mm in the course's frame.
        z: f64,
        /// The course's axial extent, mm in its frame (start).
        z0: f64,
        /// The course's axial extent, mm in its frame (end).
        z1: f64,
    },
    /// No host patch holds the whole loop and no run of neighbouring patches
    /// holds it across their seam: `cause` is why the patch tried last refused it.
    #[error("the opening does not lie within any one host patch ({cause})")]
    NotWithinPatch {
        /// Why the last patch tried refused it.
        cause: Box<CutError>,
    },
    /// A loop that goes round a head's pole could not be given its sample on the
    /// host's seam angle.
    #[error(
        "{which} goes round the pole of {patch:?} but no sample of it was found on the \
         patch's seam at u = {u}{}",
        source.as_ref().map(|e| format!(": {e}")).unwrap_or_default()
    )]
    PoleSeamSample {
        /// The loop.
        which: CutLoop,
        /// The host patch.
        patch: &'static str,
        /// The seam angle, the host's u.
        u: f64,
        /// The kernel's reason, if a solve failed.
        source: Option<NurbsError>,
    },
    /// An opening across the seam between two host patches also goes round the
    /// head's pole.
    #[error(
        "the opening crosses the seam between host patches {patches:?} and goes round the \
         head's pole; such an opening is not supported: move the nozzle off the centre \
         or inside one patch"
    )]
    AcrossSeamRoundPole {
        /// The host patches, in order along v.
        patches: Vec<&'static str>,
    },
    /// A nozzle with a reinforcing pad whose opening crosses a seam between host
    /// patches other than a knuckle and the crown, cone or plate tangent to it.
    #[error(
        "the reinforcing pad crosses the seam between host patches {patches:?}; a pad may \
         cross only one seam, between a head's knuckle and the crown, cone or plate \
         tangent to it: make the pad smaller or move the nozzle inside one patch"
    )]
    PadAcrossSeam {
        /// The host patches, in order along v.
        patches: Vec<&'static str>,
    },
    /// The loop's crossing of a seam between host patches could not be placed.
    #[error(
        "the opening crosses the seam between host patches {patches:?}, but its crossing \
         at v = {v} was not found{}",
        source.as_ref().map(|e| format!(": {e}")).unwrap_or_default()
    )]
    SeamCrossing {
        /// The host patches, in order along v.
        patches: Vec<&'static str>,
        /// The seam, v of the joined patches.
        v: f64,
        /// The kernel's reason, if a solve failed.
        source: Option<NurbsError>,
    },
    /// The loop on the joined host patches meets their seam fewer than twice.
    #[error("the opening does not cross the seam between host patches {patches:?}")]
    NotAcrossSeam {
        /// The host patches, in order along v.
        patches: Vec<&'static str>,
    },
    /// The loop touches a seam between host patches without crossing it.
    #[error(
        "the opening touches the seam between {below:?} and {above:?} without crossing it; \
         move the nozzle into one patch or across the seam"
    )]
    TouchesSeam {
        /// The patch below the seam.
        below: &'static str,
        /// The patch above it.
        above: &'static str,
    },
    /// The loop crosses a whole host patch, from one seam to the next.
    #[error(
        "the opening crosses the whole {patch:?} patch, from the seam with {below:?} to the \
         seam with {above:?}; an opening may cross one seam only: make it smaller or move it"
    )]
    CrossesWholePatch {
        /// The patch crossed.
        patch: &'static str,
        /// The patch below it.
        below: &'static str,
        /// The patch above it.
        above: &'static str,
    },
}

impl CutError {
    /// The host patch the failure names, if one.
    pub fn patch(&self) -> Option<&'static str> {
        match self {
            CutError::Intersection { patch, .. }
            | CutError::PastCourseEnd { patch, .. }
            | CutError::NotACourse { patch }
            | CutError::PoleSeamSample { patch, .. }
            | CutError::CrossesWholePatch { patch, .. } => Some(patch),
            CutError::TouchesSeam { below, .. } => Some(below),
            CutError::NotWithinPatch { cause } => cause.patch(),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::{DAffine3, DVec3};

    use super::{CutError, CutLoop};
    use crate::mesh::cut::cut_opening;
    use crate::mesh::test_parts::{course, frame, neck};
    use crate::nurbs::NurbsError;

    /// A neck that passes beside its course is refused with the loop, the host
    /// patch and the kernel's reason, not a sentence to parse.
    #[test]
    fn a_neck_beside_its_host_names_the_loop_and_the_patch() {
        let (course, neck) = (course(), neck(300.0));
        // Along x, 5 m off the course's axis (radius 1 m): it meets nothing.
        let beside = frame(DVec3::new(0.0, 5000.0, 1500.0), DVec3::X);
        let err =
            cut_opening(&neck, None, &beside, &DAffine3::IDENTITY, &[&course], 1.0).unwrap_err();
        let CutError::Intersection {
            which,
            patch,
            source,
        } = &err
        else {
            panic!("{err}");
        };
        assert_eq!((*which, *patch), (CutLoop::Neck, course.name), "{err}");
        assert!(
            matches!(source, NurbsError::GeneratorMissesHost { .. }),
            "{err}"
        );
        assert_eq!(err.patch(), Some(course.name));
        let text = err.to_string();
        assert!(
            text.contains("the neck's loop") && text.contains(course.name),
            "{text}"
        );
    }
}
