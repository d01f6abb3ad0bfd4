//! Ordered grids on disk, for `vesselcad scan interpolate`: a CMM's rows and
//! columns of points read from text, and the interpolating surface written as
//! JSON (degrees, clamped knots, control points, data parameters, residual).
//!
//! Layout: one point a line, `x y z` (spaces, tabs, commas or semicolons; more
//! columns ignored); rows separated by one or more blank lines (gnuplot's grid
//! layout); `#` and `//` comments; one header line of column names allowed
//! before the first point. Row `i` runs along the surface's u, its points along
//! v. Every row must hold as many points as the first: a ragged grid is refused
//! with the row, its first line and both counts.

use std::path::Path;

use glam::DVec3;
use serde_json::json;

use super::ScanError;
use super::error::bad;
use super::grid::{GridFit, Parametrization};
use super::points::xyz_line;

/// An ordered grid: `rows × columns` points, `points[i * columns + j]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// The points, row by row.
    pub points: Vec<DVec3>,
    /// Rows (along u).
    pub rows: usize,
    /// Points per row (along v).
    pub columns: usize,
}

/// Reads the grid of `path` (layout in the module's note).
///
/// # Errors
///
/// [`ScanError::Io`] when the file cannot be read; [`ScanError::Points`] (file,
/// line, what) for a line that is not three finite numbers, a row whose point
/// count differs from the first row's (naming the row), or fewer than two rows
/// or columns.
pub fn read_grid(path: &Path) -> Result<Grid, ScanError> {
    let text = std::fs::read_to_string(path).map_err(|e| ScanError::io(path, e))?;
    parse_grid(path, &text)
}

/// [`read_grid`] on text already read (`path` only names it in errors).
///
/// # Errors
///
/// As [`read_grid`].
pub fn parse_grid(path: &Path, text: &str) -> Result<Grid, ScanError> {
    let mut points = Vec::new();
    // (first line, point count) of each row.
    let mut rows: Vec<(u64, usize)> = Vec::new();
    let mut in_row = false;
    let mut seen_data = false;
    for (i, line) in text.lines().enumerate() {
        let number = i as u64 + 1;
        let line = line.trim();
        if line.is_empty() {
            in_row = false;
            continue;
        }
        if line.starts_with('#') || line.starts_with("//") {
            continue;
        }
        let Some(point) = xyz_line(line, !seen_data).map_err(|m| bad(path, number, m))? else {
            seen_data = true;
            continue;
        };
        seen_data = true;
        if !in_row {
            rows.push((number, 0));
            in_row = true;
        }
        if let Some(row) = rows.last_mut() {
            row.1 += 1;
        }
        points.push(point);
    }
    let Some(&(first_line, columns)) = rows.first() else {
        return Err(bad(path, 1, "no points: a grid needs rows of x y z"));
    };
    for (k, &(line, count)) in rows.iter().enumerate().skip(1) {
        if count != columns {
            return Err(bad(
                path,
                line,
                format!(
                    "row {} has {count} points, row 1 (line {first_line}) has {columns}: \
                     every row of a grid must hold the same number of points",
                    k + 1
                ),
            ));
        }
    }
    if rows.len() < 2 || columns < 2 {
        return Err(bad(
            path,
            first_line,
            format!(
                "{} rows of {columns} points: a grid needs at least 2 rows of at least 2 points \
                 (rows are separated by blank lines)",
                rows.len()
            ),
        ));
    }
    Ok(Grid {
        points,
        rows: rows.len(),
        columns,
    })
}

/// The largest distance between the surface at each grid point's parameters
/// and the point, mm.
pub fn max_residual(fit: &GridFit, grid: &Grid) -> f64 {
    let mut worst: f64 = 0.0;
    for (i, &u) in fit.u.iter().enumerate() {
        for (j, &v) in fit.v.iter().enumerate() {
            let gap = (fit.surface.point(u, v) - grid.points[i * grid.columns + j]).length();
            worst = worst.max(gap);
        }
    }
    worst
}

/// The surface as JSON: `degree_u`, `degree_v`, `knots_u`, `knots_v`,
/// `control_points` (`[x, y, z]`, row-major: `count_u × count_v`, index
/// `i * count_v + j`, `i` along u; weights are all 1), the data parameters
/// `parameters_u` (one a row) and `parameters_v` (one a column), and
/// `max_residual_mm` at the grid points.
pub fn surface_json(fit: &GridFit, parametrization: Parametrization, residual: f64) -> String {
    let s = &fit.surface;
    let poles: Vec<[f64; 3]> = s
        .control_points()
        .into_iter()
        .map(|p| p.to_array())
        .collect();
    let value = json!({
        "kind": "b-spline surface",
        "units": "mm",
        "degree_u": s.u_degree(),
        "degree_v": s.v_degree(),
        "count_u": s.u_count(),
        "count_v": s.v_count(),
        "knots_u": s.u_knots().as_slice(),
        "knots_v": s.v_knots().as_slice(),
        "control_points": poles,
        "parametrization": format!("{parametrization:?}"),
        "parameters_u": fit.u,
        "parameters_v": fit.v,
        "max_residual_mm": residual,
    });
    serde_json::to_string_pretty(&value).unwrap_or_default()
}
