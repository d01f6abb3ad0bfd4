//! Reading and writing design files: JSON with exact error paths, inch conversion,
//! validation of every rule, and a canonical save (load → save → load is identity).
//!
//! A design file is one JSON object in UTF-8 text (a leading byte-order mark is
//! skipped), a regular file of at most [`MAX_DESIGN_BYTES`]; anything after the
//! object, another file type or a larger file is refused with an error naming
//! the file and the reason.

use std::io::Read;
use std::path::Path;

use crate::constraints::ShowValue;
use crate::format::error::{DesignError, RuleViolation};
use crate::format::schema::{Design, FORMAT, Units};
use crate::format::units::to_millimetres;

/// The largest design file read, bytes (64 MiB: a 3,000-vessel plant is about
/// 10 MB).
pub const MAX_DESIGN_BYTES: u64 = 64 << 20;

/// Parses a design from JSON text, converts it to mm and checks every rule.
/// Violations in an inch file show the value as written, in inches.
pub fn parse(text: &str) -> Result<Design, DesignError> {
    let mut design = parse_unchecked(text)?;
    let units = design.units;
    to_millimetres(&mut design);
    super::validate::validate(&design).map_err(|e| match (e, units) {
        (DesignError::Invalid(violations), Units::In) => {
            DesignError::Invalid(as_written_in_inches(text, violations))
        }
        (e, _) => e,
    })?;
    Ok(design)
}

/// Shows each violated value of an inch file as written (`48 in (= 1219.2 mm)`),
/// not only as converted: a huge value converted to mm may even read `inf`.
fn as_written_in_inches(text: &str, violations: Vec<RuleViolation>) -> Vec<RuleViolation> {
    let Ok(raw) = serde_json::from_str::<serde_json::Value>(strip_bom(text)) else {
        return violations;
    };
    violations
        .into_iter()
        .map(|mut v| {
            if let Some(written) = value_at(&raw, &v.path).and_then(serde_json::Value::as_f64)
                && v.value.parse::<f64>().is_ok_and(|mm| mm != written)
            {
                v.value = if v.value.parse::<f64>().is_ok_and(f64::is_finite) {
                    format!("{} in (= {} mm)", written.show(), v.value)
                } else {
                    format!("{} in", written.show())
                };
            }
            v
        })
        .collect()
}

/// The value at a violation's path (`vessels[0].parts[1].shell.length`) in raw
/// JSON.
fn value_at<'a>(raw: &'a serde_json::Value, path: &str) -> Option<&'a serde_json::Value> {
    let mut here = raw;
    for segment in path.split('.') {
        let (name, mut rest) = match segment.find('[') {
            Some(k) => segment.split_at(k),
            None => (segment, ""),
        };
        if !name.is_empty() {
            here = here.get(name)?;
        }
        while let Some(inner) = rest.strip_prefix('[') {
            let end = inner.find(']')?;
            here = here.get(inner[..end].parse::<usize>().ok()?)?;
            rest = &inner[end + 1..];
        }
    }
    Some(here)
}

/// The text without a leading UTF-8 byte-order mark (which some editors write).
fn strip_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// Parses JSON into a design without unit conversion or rule checks; errors carry
/// the JSON path and the line and column. Content after the design's object is
/// refused.
pub fn parse_unchecked(text: &str) -> Result<Design, DesignError> {
    let text = strip_bom(text);
    check_top_level_object(text)?;
    let de = &mut serde_json::Deserializer::from_str(text);
    let design: Design = serde_path_to_error::deserialize(&mut *de).map_err(|e| {
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
    de.end().map_err(|e| DesignError::Syntax {
        path: ".".into(),
        message: format!(
            "unexpected content after the design's JSON object at line {} column {}: \
             a design file holds exactly one object (two designs concatenated?)",
            e.line(),
            e.column()
        ),
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
    let bytes = read_design_bytes(path)?;
    parse(decode_design(path, &bytes)?)
}

/// Reads a design file's bytes: a regular file (or a link to one) of at most
/// [`MAX_DESIGN_BYTES`].
///
/// # Errors
///
/// [`DesignError::Io`] when the file cannot be read, is not a regular file (a
/// folder, a device such as `/dev/zero`, a pipe) or is larger than the limit.
pub fn read_design_bytes(path: &Path) -> Result<Vec<u8>, DesignError> {
    let io = |source| DesignError::Io {
        path: path.display().to_string(),
        source,
    };
    let refuse = |message: String| {
        io(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            message,
        ))
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let meta = file.metadata().map_err(io)?;
    if !meta.is_file() {
        let kind = if meta.is_dir() {
            "a folder"
        } else {
            "a device, pipe or socket"
        };
        return Err(refuse(format!(
            "it is {kind}, not a regular file; a design is a JSON file"
        )));
    }
    if meta.len() > MAX_DESIGN_BYTES {
        return Err(refuse(format!(
            "it is {} bytes; a design file may be at most {MAX_DESIGN_BYTES} bytes",
            meta.len()
        )));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // Bounded even if the file grows while it is read.
    file.take(MAX_DESIGN_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > MAX_DESIGN_BYTES {
        return Err(refuse(format!(
            "it grew past {MAX_DESIGN_BYTES} bytes while it was read"
        )));
    }
    Ok(bytes)
}

/// A design file's bytes as text: UTF-8 (a leading byte-order mark is skipped by
/// the parser).
///
/// # Errors
///
/// [`DesignError::Syntax`] naming the encoding found (UTF-16) or the line,
/// column and byte of the first invalid UTF-8 sequence.
pub fn decode_design<'a>(path: &Path, bytes: &'a [u8]) -> Result<&'a str, DesignError> {
    let syntax = |message: String| DesignError::Syntax {
        path: ".".into(),
        message: format!("{}: {message}", path.display()),
    };
    if bytes.starts_with(&[0xFF, 0xFE]) || bytes.starts_with(&[0xFE, 0xFF]) {
        return Err(syntax(
            "the file is UTF-16 text (it starts with a UTF-16 byte-order mark); \
             a design file is UTF-8: save it as UTF-8"
                .into(),
        ));
    }
    std::str::from_utf8(bytes).map_err(|e| {
        let good = &bytes[..e.valid_up_to()];
        let line = good.iter().filter(|&&b| b == b'\n').count() + 1;
        let column = good.iter().rev().take_while(|&&b| b != b'\n').count() + 1;
        syntax(format!(
            "not UTF-8 text: byte 0x{:02X} at line {line} column {column} (byte offset {}) \
             does not start a valid UTF-8 character; a design file is UTF-8",
            bytes[e.valid_up_to()],
            e.valid_up_to()
        ))
    })
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
