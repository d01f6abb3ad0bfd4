//! IGES 5.3 file layout: the fixed 80-column records of the Start (S), Global
//! (G), Directory Entry (D), Parameter Data (P) and Terminate (T) sections.
//!
//! [`IgesWriter`] appends entities in order: each gets its two Directory Entry
//! lines (type, level, colour, status, form, label) and its parameters laid out
//! in columns 1–64 of the Parameter Data lines, with the pointer back to its
//! entry in columns 66–72. Entities refer to each other by the sequence number
//! of their first Directory Entry line ([`IgesWriter::entity`] returns it), so a
//! parent is written after its children. Reals are written shortest round-trip
//! (`ryu`), strings as Hollerith constants (`5HV-101`), ASCII only: a character
//! outside printable ASCII is written `?`, which keeps every record 80 columns.
//! [`IgesWriter::finish`] adds the Start and Global sections (units mm) and the
//! Terminate line; with a fixed date the bytes depend on the entities alone.

use std::fmt::Write as _;

use super::step::real;

/// Status numbers (blank, subordinate, entity use, hierarchy).
pub(super) mod status {
    /// An independent geometric entity.
    pub const INDEPENDENT: &str = "00000000";
    /// A physically dependent geometric entity (model space).
    pub const DEPENDENT: &str = "00010000";
    /// A physically dependent curve in a surface's parameter space.
    pub const PARAMETRIC: &str = "00010500";
    /// A definition (colour, name property).
    pub const DEFINITION: &str = "00000200";
}

/// The parameters of one entity, as tokens.
#[derive(Default)]
pub(super) struct Params {
    text: String,
    ends: Vec<usize>,
}

impl Params {
    fn token(&mut self) -> &mut Self {
        self.ends.push(self.text.len());
        self
    }

    /// An integer.
    pub(super) fn int(&mut self, x: i64) -> &mut Self {
        let _ = write!(self.text, "{x}");
        self.token()
    }

    /// A pointer to an entity (its Directory Entry sequence number).
    pub(super) fn ptr(&mut self, de: usize) -> &mut Self {
        let _ = write!(self.text, "{de}");
        self.token()
    }

    /// A real.
    pub(super) fn real(&mut self, x: f64) -> &mut Self {
        real(&mut self.text, x);
        self.token()
    }

    /// Several reals.
    pub(super) fn reals(&mut self, xs: impl IntoIterator<Item = f64>) -> &mut Self {
        for x in xs {
            self.real(x);
        }
        self
    }

    /// A string, as a Hollerith constant.
    pub(super) fn string(&mut self, s: &str) -> &mut Self {
        hollerith(&mut self.text, s);
        self.token()
    }

    /// The tokens in order.
    fn tokens(&self) -> impl Iterator<Item = &str> {
        let mut start = 0;
        self.ends.iter().map(move |&end| {
            let t = &self.text[start..end];
            start = end;
            t
        })
    }
}

/// Appends `s` as a Hollerith constant, non-printable-ASCII characters as `?`.
fn hollerith(out: &mut String, s: &str) {
    let _ = write!(out, "{}H", s.chars().count());
    out.extend(
        s.chars()
            .map(|c| if (' '..='~').contains(&c) { c } else { '?' }),
    );
}

/// One entity's Directory Entry fields.
pub(super) struct Entry {
    /// Entity type number.
    pub(super) kind: u16,
    /// Form number.
    pub(super) form: u16,
    /// Level (layer).
    pub(super) level: usize,
    /// Colour: a pointer to a colour definition, or 0.
    pub(super) colour: usize,
    /// Status number, [`status`].
    pub(super) status: &'static str,
    /// Entity label, up to 8 characters.
    pub(super) label: &'static str,
    /// Entity subscript.
    pub(super) subscript: usize,
}

/// The file's Global section values that vary.
pub(super) struct Global<'a> {
    /// The file's name.
    pub(super) name: &'a str,
    /// Smallest distance the model resolves, mm.
    pub(super) resolution: f64,
    /// Largest absolute coordinate, mm.
    pub(super) max_coordinate: f64,
}

/// Lays out the tokens in `width`-column lines, each token followed by its
/// delimiter (`,`, the last one `;`), a token too long for a line broken over
/// several (only strings are that long); calls `line` with each line's text.
fn lay_out<'a>(tokens: impl Iterator<Item = &'a str>, width: usize, mut line: impl FnMut(&str)) {
    let mut current = String::with_capacity(width);
    let mut tokens = tokens.peekable();
    while let Some(t) = tokens.next() {
        let delimiter = if tokens.peek().is_some() { ',' } else { ';' };
        let fits_a_line = t.len() < width;
        if fits_a_line && current.len() + t.len() + 1 > width {
            line(&current);
            current.clear();
        }
        let mut rest = t;
        while current.len() + rest.len() + 1 > width {
            let (head, tail) = rest.split_at(width - current.len());
            current.push_str(head);
            line(&current);
            current.clear();
            rest = tail;
        }
        current.push_str(rest);
        current.push(delimiter);
    }
    if !current.is_empty() {
        line(&current);
    }
}

/// Entities being written.
#[derive(Default)]
pub(super) struct IgesWriter {
    directory: String,
    parameters: String,
    /// Directory Entry lines written.
    d_lines: usize,
    /// Parameter Data lines written.
    p_lines: usize,
}

impl IgesWriter {
    /// Appends an entity; returns its pointer (the sequence number of its first
    /// Directory Entry line).
    pub(super) fn entity(&mut self, entry: &Entry, params: &Params) -> usize {
        let de = self.d_lines + 1;
        let first = self.p_lines + 1;
        let mut count = 0;
        let kind = entry.kind;
        let (parameters, p_lines) = (&mut self.parameters, &mut self.p_lines);
        let head = kind.to_string();
        lay_out(
            std::iter::once(head.as_str()).chain(params.tokens()),
            64,
            |text| {
                *p_lines += 1;
                count += 1;
                let _ = writeln!(parameters, "{text:<64} {de:>7}P{:>7}", *p_lines);
            },
        );
        let _ = writeln!(
            self.directory,
            "{kind:>8}{first:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}D{de:>7}",
            0, 0, entry.level, 0, 0, 0, entry.status
        );
        let colour = if entry.colour == 0 {
            0
        } else {
            -(entry.colour as i64)
        };
        let _ = writeln!(
            self.directory,
            "{kind:>8}{:>8}{colour:>8}{count:>8}{:>8}{:>8}{:>8}{:>8}{:>8}D{:>7}",
            0,
            entry.form,
            "",
            "",
            entry.label,
            entry.subscript,
            de + 1
        );
        self.d_lines += 2;
        de
    }

    /// The whole file: Start, Global, the entities, Terminate.
    pub(super) fn finish(self, global: &Global) -> String {
        let mut out = String::with_capacity(self.directory.len() + self.parameters.len() + 2048);
        let start: String = format!("vesselcad exact model: {}", global.name)
            .chars()
            .map(|c| if (' '..='~').contains(&c) { c } else { '?' })
            .collect();
        let mut s_lines = 0;
        lay_out(std::iter::once(start.as_str()), 73, |text| {
            s_lines += 1;
            // The Start section is free text: no delimiter.
            let text = text.strip_suffix(';').unwrap_or(text);
            let _ = writeln!(out, "{text:<72}S{s_lines:>7}");
        });
        let date = "19700101.000000";
        let mut g = Params::default();
        g.string(",").string(";");
        g.string(global.name).string(global.name);
        g.string("vesselcad").string(env!("CARGO_PKG_VERSION"));
        g.int(32).int(38).int(6).int(308).int(15);
        g.string(global.name).real(1.0).int(2).string("MM");
        g.int(1).real(1.0).string(date);
        g.real(global.resolution).real(global.max_coordinate);
        g.string("").string("").int(11).int(0).string(date);
        let mut g_lines = 0;
        lay_out(g.tokens(), 72, |text| {
            g_lines += 1;
            let _ = writeln!(out, "{text:<72}G{g_lines:>7}");
        });
        out.push_str(&self.directory);
        out.push_str(&self.parameters);
        let _ = writeln!(
            out,
            "S{s_lines:>7}G{g_lines:>7}D{:>7}P{:>7}{:>40}T{:>7}",
            self.d_lines, self.p_lines, "", 1
        );
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every record is 80 columns with its section letter in column 73, and a
    /// long string breaks across Parameter Data lines.
    #[test]
    fn records_are_80_columns() {
        let mut w = IgesWriter::default();
        let mut p = Params::default();
        p.int(1).string(&"x".repeat(150)).reals([1.5, -2e-20]);
        let de = w.entity(
            &Entry {
                kind: 406,
                form: 15,
                level: 1,
                colour: 0,
                status: status::DEFINITION,
                label: "NAME",
                subscript: 1,
            },
            &p,
        );
        assert_eq!(de, 1);
        let text = w.finish(&Global {
            name: "t.igs",
            resolution: 1e-3,
            max_coordinate: 10.0,
        });
        for line in text.lines() {
            assert_eq!(line.len(), 80, "{line:?}");
            assert!("SGDPT".contains(&line[72..73]), "{line:?}");
        }
        assert!(text.contains("406,1,150Hxxx"));
        assert!(text.contains(",1.5,-2.0E-20;"));
    }
}
