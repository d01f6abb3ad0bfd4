//! The glTF writer's small material palette, chosen by what a node stands for:
//! pressure parts grey, supports darker, nozzles and flanges a distinct colour.
//!
//! Part of the glTF writer ([`super::gltf_document`]): only the materials a scene
//! uses are written, always in palette order, so the material indices of a scene
//! do not depend on the order its nodes are visited in.

use gltf_json as json;
use json::material::{AlphaMode, EmissiveFactor, PbrBaseColorFactor, StrengthFactor};
use json::validation::Checked;

use super::scene::{SceneNode, SceneNodeKind};

/// The material of a scene node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum MaterialKind {
    /// Shell courses, heads, reducers, boots.
    Vessel,
    /// Skirts, saddles, legs, lugs.
    Support,
    /// Nozzle necks and flanges.
    Nozzle,
}

impl MaterialKind {
    /// Every material, in palette (and file) order.
    pub const ALL: [MaterialKind; 3] = [
        MaterialKind::Vessel,
        MaterialKind::Support,
        MaterialKind::Nozzle,
    ];

    /// The material of a node: nozzles by their node kind, parts by the `kind` of
    /// their `extras` (a part without one counts as a pressure part).
    pub fn of(node: &SceneNode) -> MaterialKind {
        // A merged node names its material.
        if let Some(kind) = node
            .extras
            .get("material")
            .and_then(|m| m.as_str())
            .and_then(|m| Self::ALL.into_iter().find(|k| k.name() == m))
        {
            return kind;
        }
        match node.kind {
            SceneNodeKind::Nozzle => MaterialKind::Nozzle,
            SceneNodeKind::Part => match node.extras.get("kind").and_then(|k| k.as_str()) {
                Some("skirt" | "saddle" | "legs" | "lugs") => MaterialKind::Support,
                _ => MaterialKind::Vessel,
            },
        }
    }

    /// Position in [`MaterialKind::ALL`].
    pub fn slot(self) -> usize {
        self as usize
    }

    /// The material's name (in the file and in merged nodes' `extras`).
    pub fn name(self) -> &'static str {
        match self {
            MaterialKind::Vessel => "vessel",
            MaterialKind::Support => "support",
            MaterialKind::Nozzle => "nozzle",
        }
    }

    /// The glTF material: opaque, metal; single-sided for the vessel and its
    /// nozzles (closed surfaces seen from outside), double-sided for supports,
    /// whose parts are open sheets seen from both sides (a skirt from inside
    /// through its opening, its base ring, a saddle's web and plates, base
    /// plates): with back-face culling, the usual default, one side of a sheet
    /// would vanish.
    pub fn material(self) -> json::Material {
        let (_, color, metallic, roughness) = match self {
            MaterialKind::Vessel => ("vessel", [0.70, 0.72, 0.74, 1.0], 0.6, 0.45),
            MaterialKind::Support => ("support", [0.32, 0.34, 0.37, 1.0], 0.5, 0.6),
            MaterialKind::Nozzle => ("nozzle", [0.86, 0.45, 0.10, 1.0], 0.5, 0.4),
        };
        json::Material {
            alpha_mode: Checked::Valid(AlphaMode::Opaque),
            double_sided: self == MaterialKind::Support,
            name: Some(self.name().to_string()),
            pbr_metallic_roughness: json::material::PbrMetallicRoughness {
                base_color_factor: PbrBaseColorFactor(color),
                metallic_factor: StrengthFactor(metallic),
                roughness_factor: StrengthFactor(roughness),
                ..Default::default()
            },
            emissive_factor: EmissiveFactor([0.0; 3]),
            ..Default::default()
        }
    }
}
