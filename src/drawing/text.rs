//! Lettering metrics: the advance width of a text in the sheet's face (DejaVu
//! Sans, the first family the SVG asks for and the one Debian's Chromium draws
//! with) and the box a [`Item::Text`](super::Item) covers on the sheet.
//!
//! The widths are the face's own advances (`hmtx`, 2048 units per em) at a font
//! size whose cap height (0.729 em) is the text's height; the SVG writer also
//! states each text's length, so a text never runs past the box the layout and
//! the collision check reserve for it, whatever face a viewer substitutes.

use glam::DVec2;

use super::sheet::{Align, Rect};

/// Advances of ASCII 32..=126 in DejaVu Sans, units of 1/2048 em.
const ASCII_ADVANCE: [u16; 95] = [
    651, 821, 942, 1716, 1303, 1946, 1597, 563, 799, 799, 1024, 1716, 651, 739, 651, 690, 1303,
    1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 1303, 690, 690, 1716, 1716, 1716, 1087, 2048,
    1401, 1405, 1430, 1577, 1294, 1178, 1587, 1540, 604, 604, 1343, 1141, 1767, 1532, 1612, 1235,
    1612, 1423, 1300, 1251, 1499, 1401, 2025, 1403, 1251, 1403, 799, 690, 799, 1716, 1024, 1024,
    1255, 1300, 1126, 1300, 1260, 721, 1300, 1298, 569, 569, 1186, 569, 1995, 1298, 1253, 1300,
    1300, 842, 1067, 803, 1298, 1212, 1675, 1212, 1212, 1075, 1303, 690, 1303, 1716,
];

/// Cap height of the face, em.
pub const CAP_HEIGHT_EM: f64 = 1493.0 / 2048.0;

/// Advance of one character, em.
fn advance(c: char) -> f64 {
    let units = match c {
        ' '..='~' => ASCII_ADVANCE[c as usize - 32],
        '°' => 1024,
        '⌀' => 1233,
        '³' | '²' => 821,
        '±' | '×' => 1716,
        '…' | '—' => 2048,
        _ => 1401,
    };
    f64::from(units) / 2048.0
}

/// Advance width of `text` at cap height `height`, mm.
pub fn text_width(text: &str, height: f64) -> f64 {
    let em = height / CAP_HEIGHT_EM;
    em * text.chars().map(advance).sum::<f64>()
}

/// The box a text covers: from the baseline less the descenders (0.3 × the cap
/// height) to a little above its capitals, along its advance; turned about the
/// insertion point by `rotation` (only multiples of 90° are used on sheets; other
/// angles give the box of the turned box).
pub fn text_box(at: DVec2, height: f64, align: Align, rotation: f64, text: &str) -> Rect {
    let w = text_width(text, height);
    let x0 = match align {
        Align::Start => 0.0,
        Align::Middle => -0.5 * w,
        Align::End => -w,
    };
    let local = [
        DVec2::new(x0, -0.3 * height),
        DVec2::new(x0 + w, -0.3 * height),
        DVec2::new(x0 + w, 1.15 * height),
        DVec2::new(x0, 1.15 * height),
    ];
    let (s, c) = rotation.to_radians().sin_cos();
    let turned = local.map(|p| at + DVec2::new(c * p.x - s * p.y, s * p.x + c * p.y));
    let min = turned.iter().copied().reduce(DVec2::min).unwrap_or(at);
    let max = turned.iter().copied().reduce(DVec2::max).unwrap_or(at);
    Rect { min, max }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn widths_are_the_faces_advances() {
        // "0" is 1303/2048 em; at cap height 1493/2048 em = 3 mm, 1 em = 4.115 mm.
        let w = text_width("00", 3.0);
        assert!((w - 2.0 * 1303.0 / 1493.0 * 3.0).abs() < 1e-9, "{w}");
        assert!(text_width("W", 2.0) > text_width("i", 2.0) * 3.0);
    }

    #[test]
    fn a_turned_box_swaps_its_sides() {
        let flat = text_box(DVec2::ZERO, 2.0, Align::Start, 0.0, "N1 EL 100");
        let up = text_box(DVec2::ZERO, 2.0, Align::Start, 90.0, "N1 EL 100");
        assert!((flat.size().x - up.size().y).abs() < 1e-9);
        assert!((flat.size().y - up.size().x).abs() < 1e-9);
        assert!(up.max.x <= 0.6 + 1e-9 && up.min.y >= -1e-9);
    }
}
