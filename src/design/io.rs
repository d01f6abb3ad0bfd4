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
    check_top_level_object(text)?;
    let de = &mut serde_json::Deserializer::from_str(text);
    let design: Design = serde_path_to_error::deserialize(de).map_err(|e| {
        // serde_path_to_error writes `?` for a segment it never learned (the key
        // being read when the JSON broke off); the enclosing object is the place.
        let path = e.path().to_string();
        let path = match path.strip_suffix("?").map(|p| p.trim_end_matches('.')) {
            Some("") => ".".to_string(),
            Some(p) => p.to_string(),
            None => path,
        };
        let inner = e.into_inner();
        let message = explain_expected_value(text, &inner)
            .unwrap_or_else(|| plain_type_names(&inner.to_string()));
        DesignError::Syntax { path, message }
    })?;
    if design.format != FORMAT {
        return Err(DesignError::Format {
            found: design.format,
            expected: FORMAT,
        });
    }
    Ok(design)
}

/// A design is a JSON object. serde would also read a struct from an array of its
/// fields in order, which gives baffling errors for a file that is not an object
/// at all, so anything but `{` (after whitespace) is rejected here, up front.
fn check_top_level_object(text: &str) -> Result<(), DesignError> {
    let Some((offset, first)) = text.char_indices().find(|(_, c)| !c.is_whitespace()) else {
        return Ok(()); // serde reports the empty file
    };
    if first == '{' {
        return Ok(());
    }
    let (line, column) = line_column(text, offset);
    Err(DesignError::Syntax {
        path: ".".into(),
        message: format!(
            "invalid type: {}, expected a JSON object {{\"format\": \"{FORMAT}\", \"vessels\": [...]}} \
             at line {line} column {column}",
            describe_token(&text[offset..])
        ),
    })
}

/// serde_json says only "expected value" when a field that takes a name (an
/// enumeration such as `kind`, `shape` or `facing`) holds a number, array, `true`,
/// `false` or `null`. Where the text at the error position is a well-formed JSON
/// value, the real problem is its type: say so.
fn explain_expected_value(text: &str, error: &serde_json::Error) -> Option<String> {
    if !error.to_string().starts_with("expected value at") {
        return None;
    }
    let (line, column) = (error.line(), error.column());
    let start = text
        .split_inclusive('\n')
        .take(line.saturating_sub(1))
        .map(str::len)
        .sum::<usize>();
    // serde_json counts columns in bytes, from 1.
    let token = text.get(start + column.checked_sub(1)?..)?;
    let first = token.chars().next()?;
    if !(first.is_ascii_digit() || matches!(first, '-' | '[' | 't' | 'f' | 'n')) {
        return None; // really malformed JSON: keep serde's message
    }
    Some(format!(
        "invalid type: {}, expected a name (a JSON string such as \"vertical\", \
         \"ellipsoidal\" or \"RF\") at line {line} column {column}",
        describe_token(token)
    ))
}

/// serde names the Rust types it expected (`f64`, `u32`, `struct ShellDesign`);
/// a designer reads JSON, so say it in JSON's words.
fn plain_type_names(message: &str) -> String {
    let mut out = message
        .replace("expected f64", "expected a number")
        .replace("expected u32", "expected a whole number ≥ 0");
    if let Some(at) = out.find("expected struct ") {
        let name_start = at + "expected struct ".len();
        let name_end = out[name_start..]
            .find(|c: char| !c.is_alphanumeric())
            .map_or(out.len(), |k| name_start + k);
        out.replace_range(at..name_end, "expected an object");
    }
    out
}

/// Line and column (both from 1, the column in bytes as serde_json counts it) of a
/// byte offset.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = text.get(..offset).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, str::len) + 1;
    (line, column)
}

/// A short description of the JSON value starting `text`, e.g. ``number `2` ``.
fn describe_token(text: &str) -> String {
    let word: String = text
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '+' | '.'))
        .take(24)
        .collect();
    match text.chars().next() {
        Some('[') => "an array".into(),
        Some('"') => "a string".into(),
        Some('{') => "an object".into(),
        Some(c) if c.is_ascii_digit() || c == '-' => format!("number `{word}`"),
        _ if !word.is_empty() => format!("`{word}`"),
        _ => "an unexpected character".into(),
    }
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
