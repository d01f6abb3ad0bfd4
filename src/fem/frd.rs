//! Reads CalculiX's ASCII results file (`.frd`): the node block (`2C`) and the
//! nodal result blocks (`-4  DISP`, `-4  STRESS`, `-4  FORC` reactions) of the last step. Records are
//! fixed-column: ` -1`, the node number in 10 columns, then values 12 columns
//! each (values can touch, so the columns are cut, not split on spaces).

use std::collections::HashMap;
use std::path::Path;

use glam::DVec3;

use super::FemError;

/// The nodal results of a run, keyed by the solver's node number (1-based; for
/// shells CalculiX numbers the expanded through-thickness nodes after the
/// model's own).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frd {
    /// Node positions.
    pub nodes: HashMap<usize, DVec3>,
    /// Displacements.
    pub displacement: HashMap<usize, DVec3>,
    /// Stresses: xx, yy, zz, xy, yz, zx.
    pub stress: HashMap<usize, [f64; 6]>,
    /// Nodal forces (`RF`), N: the reactions at restrained nodes (at free
    /// nodes they balance the applied loads).
    pub reactions: HashMap<usize, DVec3>,
}

/// One ` -1` record: node number and values.
fn record(line: &str) -> Option<(usize, Vec<f64>)> {
    let id = line.get(3..13)?.trim().parse().ok()?;
    let mut values = Vec::new();
    let mut at = 13;
    while at + 12 <= line.len() {
        values.push(line.get(at..at + 12)?.trim().parse().ok()?);
        at += 12;
    }
    Some((id, values))
}

/// Parses `.frd` text; `path` names it in errors.
///
/// # Errors
///
/// [`FemError::Frd`] for a record that does not read, or a file with no node
/// block.
pub fn parse(path: &Path, text: &str) -> Result<Frd, FemError> {
    #[derive(PartialEq)]
    enum Block {
        None,
        Nodes,
        Disp,
        Stress,
        Forces,
    }
    let mut out = Frd::default();
    let mut block = Block::None;
    for (k, line) in text.lines().enumerate() {
        let t = line.trim_start();
        if t.starts_with("2C") {
            block = Block::Nodes;
            continue;
        }
        if let Some(rest) = t.strip_prefix("-4") {
            let name = rest.split_whitespace().next().unwrap_or("");
            block = match name {
                "DISP" => Block::Disp,
                "STRESS" => Block::Stress,
                "FORC" => Block::Forces,
                _ => Block::None,
            };
            continue;
        }
        if t.starts_with("-3") || t.starts_with("3C") || t.starts_with("9999") {
            block = Block::None;
            continue;
        }
        if block == Block::None || !line.starts_with(" -1") {
            continue;
        }
        let bad = |message: &str| FemError::Frd {
            path: path.to_path_buf(),
            line: k + 1,
            message: message.into(),
        };
        let (id, v) = record(line).ok_or_else(|| bad("a ` -1` record that does not read"))?;
        match block {
            Block::Nodes if v.len() >= 3 => {
                out.nodes.insert(id, DVec3::new(v[0], v[1], v[2]));
            }
            Block::Disp if v.len() >= 3 => {
                out.displacement.insert(id, DVec3::new(v[0], v[1], v[2]));
            }
            Block::Forces if v.len() >= 3 => {
                out.reactions.insert(id, DVec3::new(v[0], v[1], v[2]));
            }
            Block::Stress if v.len() >= 6 => {
                out.stress.insert(id, [v[0], v[1], v[2], v[3], v[4], v[5]]);
            }
            _ => return Err(bad("too few values in the record")),
        }
    }
    if out.nodes.is_empty() {
        return Err(FemError::Frd {
            path: path.to_path_buf(),
            line: 0,
            message: "no node block (2C)".into(),
        });
    }
    Ok(out)
}

/// Reads and parses the `.frd` file at `path`.
///
/// # Errors
///
/// [`FemError::Io`] when it cannot be read, else as [`parse`].
pub fn read(path: &Path) -> Result<Frd, FemError> {
    let text = std::fs::read_to_string(path).map_err(|source| FemError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse(path, &text)
}
