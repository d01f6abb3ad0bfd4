//! Reading vesselcad's GLB files back in every variant the writer has — `f32`,
//! `KHR_mesh_quantization` (`u16` positions, normalized `i8` normals, `u16`
//! indices), `EXT_meshopt_compression` (views decoded with the meshopt crate) —
//! independently of the writer, and the Khronos validator on a file.

use std::path::Path;
use std::process::Command;

use glam::{DMat4, DQuat, DVec3};
use serde_json::Value;

/// A parsed GLB: its JSON and its buffer views' bytes (decoded when compressed).
pub struct Glb {
    pub json: Value,
    views: Vec<Vec<u8>>,
}

/// One primitive's data: positions and normals (none for a file without
/// them) in the mesh's own numbers
/// (dequantized only by the accessor's normalization), and indices.
pub struct Primitive {
    pub positions: Vec<DVec3>,
    pub normals: Vec<DVec3>,
    pub indices: Vec<u32>,
}

impl Glb {
    /// Parses a GLB container and decodes every buffer view.
    pub fn parse(bytes: &[u8]) -> Glb {
        assert_eq!(&bytes[0..4], b"glTF");
        let u32_at = |k: usize| u32::from_le_bytes(bytes[k..k + 4].try_into().unwrap()) as usize;
        assert_eq!(u32_at(8), bytes.len());
        let json_len = u32_at(12);
        assert_eq!(&bytes[16..20], b"JSON");
        let json: Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
        let bin_at = 20 + json_len;
        let bin: &[u8] = if bin_at < bytes.len() {
            assert_eq!(&bytes[bin_at + 4..bin_at + 8], b"BIN\0");
            &bytes[bin_at + 8..bin_at + 8 + u32_at(bin_at)]
        } else {
            &[]
        };
        let mut views = Vec::new();
        for view in json["bufferViews"].as_array().into_iter().flatten() {
            let ext = &view["extensions"]["EXT_meshopt_compression"];
            if ext.is_object() {
                assert_eq!(ext["buffer"], 0, "compressed data lies in the BIN chunk");
                let at = ext["byteOffset"].as_u64().unwrap_or(0) as usize;
                let len = ext["byteLength"].as_u64().unwrap() as usize;
                let stride = ext["byteStride"].as_u64().unwrap() as usize;
                let count = ext["count"].as_u64().unwrap() as usize;
                let data = &bin[at..at + len];
                let decoded: Vec<u8> = match (ext["mode"].as_str().unwrap(), stride) {
                    ("ATTRIBUTES", 4) if ext["filter"] == "OCTAHEDRAL" => {
                        let mut oct: Vec<[i8; 4]> =
                            meshopt::decode_vertex_buffer::<[u8; 4]>(data, count)
                                .unwrap()
                                .iter()
                                .map(|v| v.map(|c| c as i8))
                                .collect();
                        meshopt::decode_filter_oct(&mut oct);
                        oct.iter().flatten().map(|&c| c as u8).collect()
                    }
                    ("ATTRIBUTES", 4) => {
                        flat(meshopt::decode_vertex_buffer::<[u8; 4]>(data, count))
                    }
                    ("ATTRIBUTES", 8) => {
                        flat(meshopt::decode_vertex_buffer::<[u8; 8]>(data, count))
                    }
                    ("ATTRIBUTES", 12) => {
                        flat(meshopt::decode_vertex_buffer::<[u8; 12]>(data, count))
                    }
                    ("TRIANGLES", 2) => meshopt::decode_index_buffer::<u16>(data, count)
                        .unwrap()
                        .iter()
                        .flat_map(|i| i.to_le_bytes())
                        .collect(),
                    ("TRIANGLES", 4) => meshopt::decode_index_buffer::<u32>(data, count)
                        .unwrap()
                        .iter()
                        .flat_map(|i| i.to_le_bytes())
                        .collect(),
                    other => panic!("unexpected meshopt view {other:?}"),
                };
                assert_eq!(decoded.len(), view["byteLength"].as_u64().unwrap() as usize);
                views.push(decoded);
            } else {
                assert_eq!(view["buffer"], 0);
                let at = view["byteOffset"].as_u64().unwrap_or(0) as usize;
                let len = view["byteLength"].as_u64().unwrap() as usize;
                views.push(bin[at..at + len].to_vec());
            }
        }
        Glb { json, views }
    }

    /// The elements of an accessor as `f64`, normalized integers mapped as the
    /// glTF specification says.
    pub fn accessor(&self, index: usize) -> Vec<Vec<f64>> {
        let a = &self.json["accessors"][index];
        let view_index = a["bufferView"].as_u64().unwrap() as usize;
        let view = &self.views[view_index];
        let stride_given = self.json["bufferViews"][view_index]["byteStride"].as_u64();
        let components = match a["type"].as_str().unwrap() {
            "SCALAR" => 1,
            "VEC3" => 3,
            "VEC4" => 4,
            other => panic!("type {other}"),
        };
        let component_type = a["componentType"].as_u64().unwrap();
        let size = match component_type {
            5120 | 5121 => 1,
            5122 | 5123 => 2,
            5125 | 5126 => 4,
            other => panic!("component type {other}"),
        };
        let normalized = a["normalized"].as_bool().unwrap_or(false);
        let stride = stride_given.map_or(size * components, |s| s as usize);
        let offset = a["byteOffset"].as_u64().unwrap_or(0) as usize;
        let count = a["count"].as_u64().unwrap() as usize;
        (0..count)
            .map(|e| {
                (0..components)
                    .map(|c| {
                        let at = offset + e * stride + c * size;
                        let b = &view[at..at + size];
                        let x = match component_type {
                            5120 => f64::from(b[0] as i8),
                            5121 => f64::from(b[0]),
                            5122 => f64::from(i16::from_le_bytes([b[0], b[1]])),
                            5123 => f64::from(u16::from_le_bytes([b[0], b[1]])),
                            5125 => f64::from(u32::from_le_bytes(b.try_into().unwrap())),
                            _ => f64::from(f32::from_le_bytes(b.try_into().unwrap())),
                        };
                        match (normalized, component_type) {
                            (true, 5120) => (x / 127.0).max(-1.0),
                            (true, 5121) => x / 255.0,
                            (true, 5122) => (x / 32767.0).max(-1.0),
                            (true, 5123) => x / 65535.0,
                            _ => x,
                        }
                    })
                    .collect()
            })
            .collect()
    }

    /// The first primitive of mesh `index`.
    pub fn primitive(&self, index: usize) -> Primitive {
        let p = &self.json["meshes"][index]["primitives"][0];
        let vec3 = |a: &Value| -> Vec<DVec3> {
            self.accessor(a.as_u64().unwrap() as usize)
                .into_iter()
                .map(|v| DVec3::new(v[0], v[1], v[2]))
                .collect()
        };
        Primitive {
            positions: vec3(&p["attributes"]["POSITION"]),
            normals: if p["attributes"]["NORMAL"].is_null() {
                Vec::new()
            } else {
                vec3(&p["attributes"]["NORMAL"])
            },
            indices: self
                .accessor(p["indices"].as_u64().unwrap() as usize)
                .into_iter()
                .map(|v| v[0] as u32)
                .collect(),
        }
    }

    /// Node `index`'s JSON.
    pub fn node(&self, index: usize) -> &Value {
        &self.json["nodes"][index]
    }

    /// The children of node `index`.
    pub fn children(&self, index: usize) -> Vec<usize> {
        self.node(index)["children"]
            .as_array()
            .map(|c| c.iter().map(|i| i.as_u64().unwrap() as usize).collect())
            .unwrap_or_default()
    }

    /// The root node of the default scene.
    pub fn root(&self) -> usize {
        let scene = self.json["scene"].as_u64().unwrap() as usize;
        self.json["scenes"][scene]["nodes"][0].as_u64().unwrap() as usize
    }

    /// Node `index`'s local transform.
    pub fn local_matrix(&self, index: usize) -> DMat4 {
        let node = self.node(index);
        let v = |key: &str, default: &[f64]| -> Vec<f64> {
            node[key]
                .as_array()
                .map(|a| a.iter().map(|x| x.as_f64().unwrap()).collect())
                .unwrap_or_else(|| default.to_vec())
        };
        let t = v("translation", &[0.0; 3]);
        let r = v("rotation", &[0.0, 0.0, 0.0, 1.0]);
        let s = v("scale", &[1.0; 3]);
        DMat4::from_scale_rotation_translation(
            DVec3::new(s[0], s[1], s[2]),
            DQuat::from_xyzw(r[0], r[1], r[2], r[3]),
            DVec3::new(t[0], t[1], t[2]),
        )
    }
}

fn flat<const N: usize>(decoded: Result<Vec<[u8; N]>, meshopt::Error>) -> Vec<u8> {
    decoded.unwrap().concat()
}

/// Runs the Khronos validator on GLB bytes; `None` when it is not installed
/// (after failing under CI).
pub fn validate(name: &str, bytes: &[u8]) -> Option<Value> {
    const MISSING: &str = "gltf-validator is not installed: run npm ci --prefix tests/support";
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let module = root.join("tests/support/node_modules/gltf-validator/package.json");
    let node = Command::new("node").arg("--version").output();
    if !module.is_file() || !node.is_ok_and(|o| o.status.success()) {
        if std::env::var_os("CI").is_some() {
            panic!("{MISSING}");
        }
        eprintln!("{MISSING}");
        return None;
    }
    let file =
        std::env::temp_dir().join(format!("vesselcad-glb-{name}-{}.glb", std::process::id()));
    std::fs::write(&file, bytes).unwrap();
    let output = Command::new("node")
        .arg(root.join("tests/support/validate-gltf.js"))
        .arg(&file)
        .output()
        .unwrap();
    std::fs::remove_file(&file).unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    Some(serde_json::from_str(&stdout).unwrap_or_else(|e| {
        panic!(
            "{name}: validator output is not JSON ({e}): {stdout}\n{}",
            String::from_utf8_lossy(&output.stderr)
        )
    }))
}
