//! Reading and writing design files: JSON with exact error paths, inch conversion,
//! validation of every rule, and a canonical save (load → save → load is identity).

use std::path::Path;

use super::error::DesignError;
use super::schema::{Design, FORMAT};
use super::units::to_millimetres;

/// Parses a design from JSON text, converts it to mm and checks every rule.
pub fn parse(text: &str) -> Result<Design, DesignError> {
    let mut design = parse_unchecked(text)?;
    to_millimetres(&mut design);
    super::validate::validate(&design)?;
    Ok(design)
}

/// Parses JSON into a design without unit conversion or rule checks; errors carry
/// the JSON path and the line and column.
pub fn parse_unchecked(text: &str) -> Result<Design, DesignError> {
    let de = &mut serde_json::Deserializer::from_str(text);
    let design: Design = serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        DesignError::Syntax {
            path,
            message: e.into_inner().to_string(),
        }
    })?;
    if design.format != FORMAT {
        return Err(DesignError::Format {
            found: design.format,
            expected: FORMAT,
        });
    }
    Ok(design)
}

/// Reads and parses a design file.
pub fn load(path: impl AsRef<Path>) -> Result<Design, DesignError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| DesignError::Io {
        path: path.display().to_string(),
        source,
    })?;
    parse(&text)
}

/// The canonical JSON text of a design: mm, fields in schema order, defaults
/// omitted, two-space indentation, a trailing newline.
pub fn to_canonical_json(design: &Design) -> String {
    // Serializing plain data with string keys cannot fail.
    let mut text = serde_json::to_string_pretty(design).unwrap_or_default();
    text.push('\n');
    text
}

/// Writes the canonical JSON of a design to `path` atomically (temp file + rename).
pub fn save(design: &Design, path: impl AsRef<Path>) -> Result<(), DesignError> {
    let path = path.as_ref();
    let io = |source| DesignError::Io {
        path: path.display().to_string(),
        source,
    };
    let tmp = path.with_extension("json.tmp");
    std::fs::write(&tmp, to_canonical_json(design)).map_err(io)?;
    std::fs::rename(&tmp, path).map_err(io)
}
