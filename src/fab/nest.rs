//! Nesting of plates, pads and head blanks onto stock sheets, by a stated
//! simple strategy: **first-fit decreasing shelves** on each piece's
//! bounding box (a cone's sector and a pad by their boxes, a blank by its
//! square). Pieces are grouped by thickness (a sheet has one); within a
//! group they are sorted by height, long side along the sheet's length where
//! they fit so, and placed left to right on shelves stacked across the
//! sheet, `nest_gap` apart. Utilisation is the pieces' net area (openings
//! taken off) over the area of the sheets used. A piece larger than a sheet
//! either way is listed as oversize (a special plate).
//!
//! A true-shape nester (`jagua-rs`) would pack sectors and pads tighter;
//! this one is exact about what it reports and needs no search.

use glam::DVec2;

/// A piece to nest.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// Id: a plate id, `C-201-N5-PAD`, `C-201-H1-BLANK`.
    pub id: String,
    /// Thickness, mm.
    pub thickness: f64,
    /// Bounding box `(width, height)`, mm.
    pub size: DVec2,
    /// Net area, mm².
    pub area: f64,
}

/// A piece placed on a sheet.
#[derive(Clone, Debug, PartialEq)]
pub struct Placed {
    /// Piece id.
    pub id: String,
    /// Lower-left corner of its box on the sheet, mm.
    pub at: DVec2,
    /// Its box as placed, mm.
    pub size: DVec2,
    /// Turned by 90° from its developed orientation.
    pub turned: bool,
}

/// One stock sheet and what is cut from it.
#[derive(Clone, Debug, PartialEq)]
pub struct Sheet {
    /// Thickness, mm.
    pub thickness: f64,
    /// `(length, width)`, mm.
    pub size: DVec2,
    /// Pieces placed.
    pub pieces: Vec<Placed>,
    /// Net area of the pieces over the sheet's area.
    pub utilisation: f64,
}

/// The nesting of one vessel.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Nesting {
    /// Sheets, by thickness, then in order of filling.
    pub sheets: Vec<Sheet>,
    /// Pieces larger than a sheet.
    pub oversize: Vec<Piece>,
    /// Net area of all nested pieces over the area of all sheets.
    pub utilisation: f64,
}

struct Shelf {
    y: f64,
    height: f64,
    x: f64,
}

/// Nests `pieces` on sheets `length × width` mm with `gap` between pieces.
pub fn nest(pieces: &[Piece], length: f64, width: f64, gap: f64) -> Nesting {
    let mut out = Nesting::default();
    let mut order: Vec<&Piece> = pieces.iter().collect();
    // Thickness groups, then tallest (short side) first, then by id.
    order.sort_by(|a, b| {
        a.thickness
            .total_cmp(&b.thickness)
            .then(b.size.min_element().total_cmp(&a.size.min_element()))
            .then(a.id.cmp(&b.id))
    });
    let mut used_area = 0.0;
    let mut net_area = 0.0;
    let mut group_start = 0;
    for piece in order {
        if out.sheets[group_start..]
            .first()
            .is_some_and(|s| s.thickness != piece.thickness)
        {
            group_start = out.sheets.len();
        }
        // Long side along the sheet's length where it fits so.
        let along = DVec2::new(piece.size.max_element(), piece.size.min_element());
        let fits = |s: DVec2| s.x <= length + 1e-9 && s.y <= width + 1e-9;
        let size = if fits(along) {
            along
        } else if fits(DVec2::new(along.y, along.x)) {
            DVec2::new(along.y, along.x)
        } else {
            out.oversize.push(piece.clone());
            continue;
        };
        let turned = size.x != piece.size.x;
        let placed = |at: DVec2| Placed {
            id: piece.id.clone(),
            at,
            size,
            turned,
        };
        let mut done = false;
        'sheets: for sheet_index in group_start..out.sheets.len() {
            let sheet = &mut out.sheets[sheet_index];
            let mut shelves = shelves_of(sheet, gap);
            for shelf in &mut shelves {
                if size.y <= shelf.height + 1e-9 && shelf.x + size.x <= length + 1e-9 {
                    sheet.pieces.push(placed(DVec2::new(shelf.x, shelf.y)));
                    done = true;
                    break 'sheets;
                }
            }
            let top = shelves.last().map_or(0.0, |s| s.y + s.height + gap);
            if top + size.y <= width + 1e-9 {
                sheet.pieces.push(placed(DVec2::new(0.0, top)));
                done = true;
                break;
            }
        }
        if !done {
            out.sheets.push(Sheet {
                thickness: piece.thickness,
                size: DVec2::new(length, width),
                pieces: vec![placed(DVec2::ZERO)],
                utilisation: 0.0,
            });
            used_area += length * width;
        }
        net_area += piece.area;
        let sheet = out
            .sheets
            .iter_mut()
            .rev()
            .find(|s| s.pieces.iter().any(|p| p.id == piece.id))
            .expect("just placed");
        sheet.utilisation += piece.area / (length * width);
    }
    out.utilisation = if used_area > 0.0 {
        net_area / used_area
    } else {
        0.0
    };
    out
}

/// The shelves of a sheet from its pieces: a shelf per distinct bottom y,
/// as tall as its first (tallest) piece, its next free x.
fn shelves_of(sheet: &Sheet, gap: f64) -> Vec<Shelf> {
    let mut shelves: Vec<Shelf> = Vec::new();
    for p in &sheet.pieces {
        match shelves.iter_mut().find(|s| s.y == p.at.y) {
            Some(s) => s.x = s.x.max(p.at.x + p.size.x + gap),
            None => shelves.push(Shelf {
                y: p.at.y,
                height: p.size.y,
                x: p.at.x + p.size.x + gap,
            }),
        }
    }
    shelves
}

#[cfg(test)]
mod tests {
    use super::*;

    fn piece(id: &str, w: f64, h: f64) -> Piece {
        Piece {
            id: id.into(),
            thickness: 10.0,
            size: DVec2::new(w, h),
            area: w * h,
        }
    }

    #[test]
    fn pieces_never_overlap_and_stay_on_their_sheet() {
        let pieces: Vec<Piece> = (0..40)
            .map(|i| {
                piece(
                    &format!("P{i}"),
                    300.0 + 37.0 * (i % 7) as f64,
                    200.0 + 53.0 * (i % 5) as f64,
                )
            })
            .collect();
        let n = nest(&pieces, 3000.0, 1500.0, 10.0);
        let placed: usize = n.sheets.iter().map(|s| s.pieces.len()).sum();
        assert_eq!(placed, 40);
        for s in &n.sheets {
            for (i, a) in s.pieces.iter().enumerate() {
                assert!(a.at.x >= 0.0 && a.at.y >= 0.0);
                assert!(a.at.x + a.size.x <= 3000.0 + 1e-9 && a.at.y + a.size.y <= 1500.0 + 1e-9);
                for b in &s.pieces[i + 1..] {
                    let apart = a.at.x + a.size.x + 10.0 - 1e-9 <= b.at.x
                        || b.at.x + b.size.x + 10.0 - 1e-9 <= a.at.x
                        || a.at.y + a.size.y + 10.0 - 1e-9 <= b.at.y
                        || b.at.y + b.size.y + 10.0 - 1e-9 <= a.at.y;
                    assert!(apart, "{} and {} overlap", a.id, b.id);
                }
            }
        }
        let total: f64 = pieces.iter().map(|p| p.area).sum();
        let sheets = n.sheets.len() as f64 * 3000.0 * 1500.0;
        assert!((n.utilisation - total / sheets).abs() < 1e-12);
        assert!(n.utilisation > 0.5, "{}", n.utilisation);
    }

    #[test]
    fn oversize_pieces_are_listed() {
        let n = nest(&[piece("BIG", 4000.0, 2000.0)], 3000.0, 1500.0, 10.0);
        assert!(n.sheets.is_empty());
        assert_eq!(n.oversize.len(), 1);
    }
}
