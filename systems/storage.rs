//! The options the patches are meshed to: those asked for
//! ([`RequestedTessellation`]) with the tolerance less the `f32` rounding of
//! the plant's largest part, so that the stored meshes (glTF `f32` metres) hold
//! the tolerance asked for (see [`storage_options`]). The rounding bound
//! changes only when the largest part crosses a power of two in metres; then
//! the options change and every patch is laid out and meshed again, as after
//! [`Model::set_tessellation`](crate::model::Model::set_tessellation).
//! `build_scene` budgets the same way from the same patches, so a full build
//! and an incremental one agree.

use crate::components::RequestedTessellation;
use bevy_ecs::query::{QueryState, With};
use bevy_ecs::world::World;

use crate::components::Tessellation;
use crate::components::{PatchOf, PatchSurface};
use crate::mesh::{patch_extent, storage_options};

/// Sets [`Tessellation`] from [`RequestedTessellation`] and the largest
/// coordinate of any part or nozzle patch in its part's frame (pads lie on
/// their hosts). Reads every patch's control points each run (a few hundred
/// thousand coordinates in a 400-vessel plant, about a thousandth of a tick's
/// instructions); writes the options only when they differ.
pub fn budget_storage_precision(
    world: &mut World,
    patches: &mut QueryState<&PatchSurface, With<PatchOf>>,
) {
    let extent = patches
        .iter(world)
        .map(|s| patch_extent(&s.0))
        .fold(0.0, f64::max);
    let options = storage_options(&world.resource::<RequestedTessellation>().0, extent);
    if world.resource::<Tessellation>().0 != options {
        world.resource_mut::<Tessellation>().0 = options;
    }
}
