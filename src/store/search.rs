//! Similar-design search over the `vessels` feature rows (each design's newest
//! revision): `--like` ranks by a distance, `--where` filters by conditions;
//! both are one plain SQL query a DBA can read and index.
//!
//! The distance between a stored vessel and the wanted one (subscript 0) is
//!
//! ```text
//! d = 4·|od − od₀|/od₀ + 2·|L − L₀|/L₀ + 2·|p − p₀|/max(p₀, 100 kPa)
//!   + |T − T₀|/200 °C + 1·[kind ≠ kind₀] + 0.5·[head ≠ head₀]
//!   + 0.5·[material ≠ material₀] + 0.1·|n − n₀| + 0.25·|N − N₀|/max(N₀, 1)
//! ```
//!
//! with `od` the largest shell OD, `L` the tangent-to-tangent length, `p`, `T`
//! the design pressure and temperature, `n` the nozzle count and `N` the largest
//! nozzle (NPS): 0 is the same vessel, 1 is e.g. a quarter off in diameter or
//! another kind. The answer is exact, in at most two queries over the covering
//! index `vessels_features` (led by `od`): the first looks only at vessels within
//! ±5 % of `od₀` (any vessel outside has `d ≥ 0.2`); if its `n`-th distance `r` is
//! not below 0.2, the second looks at the box that holds every vessel with
//! `d ≤ r` (`|od − od₀| ≤ r·od₀/4`, `|L − L₀| ≤ r·L₀/2`, `|p − p₀| ≤ r·max(p₀, 100)/2`,
//! `|T − T₀| ≤ 200·r`), and at every vessel when the first found fewer than `n`.
//!
//! A `--where` condition is `field op value` joined by `and`, with `op` one of
//! `= != < <= > >=` or `between a and b`; numeric fields `od length pressure
//! temperature nozzles max_nozzle nozzle_total`, text fields `kind head material
//! tag design` (text values in quotes or bare words).

use serde::Serialize;

use super::backend::SqlValue;
use super::error::StoreError;
use super::features::Features;
use super::open::Store;

/// One vessel found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Hit {
    /// The design it is in.
    pub design: String,
    /// The revision its features were last changed in.
    pub rev: i64,
    /// Its features.
    pub features: Features,
    /// Its distance from the wanted vessel (`--like` only).
    pub distance: Option<f64>,
}

/// The fields a `--where` may name: (name, numeric).
const FIELDS: &[(&str, bool)] = &[
    ("od", true),
    ("length", true),
    ("pressure", true),
    ("temperature", true),
    ("nozzles", true),
    ("max_nozzle", true),
    ("nozzle_total", true),
    ("kind", false),
    ("head", false),
    ("material", false),
    ("tag", false),
    ("design", false),
];

/// The first look of `--like`: vessels within this fraction of the wanted OD.
const NEAR: f64 = 0.05;

/// The columns every search returns, in [`Hit`] order.
const COLUMNS: &str = "design, rev, tag, kind, head, material, od, length, pressure, \
                       temperature, nozzles, max_nozzle, nozzle_total";

/// The distance as SQL; parameters `$1`…`$10` are the wanted vessel's.
const DISTANCE: &str = "CAST(4.0 * abs(od - $1) / $1 + 2.0 * abs(length - $2) / $2
       + 2.0 * abs(pressure - $3) / $4 + abs(temperature - $5) / 200.0
       + CASE WHEN kind = $6 THEN 0.0 ELSE 1.0 END
       + CASE WHEN head = $7 THEN 0.0 ELSE 0.5 END
       + CASE WHEN material = $8 THEN 0.0 ELSE 0.5 END
       + 0.1 * abs(nozzles - $9) + 0.25 * abs(max_nozzle - $10) / $11 AS DOUBLE PRECISION)";

/// A parsed `--where`: SQL with placeholders from `$first`, and its values.
#[derive(Debug)]
pub struct Condition {
    sql: String,
    params: Vec<SqlValue>,
}

impl Condition {
    /// Parses `text`; placeholders are numbered from `first`.
    ///
    /// # Errors
    ///
    /// [`StoreError::Search`] naming the word that cannot be read and what was
    /// expected there.
    pub fn parse(text: &str, first: usize) -> Result<Condition, StoreError> {
        let words = tokens(text)?;
        let mut k = 0;
        let mut parts = Vec::new();
        let mut params = Vec::new();
        let fail = |at: usize, expected: &str| {
            StoreError::Search(format!(
                "in --where {text:?}: expected {expected} at {}",
                words
                    .get(at)
                    .map_or("the end".to_string(), |w| format!("{:?}", w.text))
            ))
        };
        loop {
            let Some(field) = words.get(k) else {
                return Err(fail(k, "a field"));
            };
            let Some(&(name, numeric)) = FIELDS
                .iter()
                .find(|(f, _)| f.eq_ignore_ascii_case(&field.text) && !field.quoted)
            else {
                let known: Vec<&str> = FIELDS.iter().map(|f| f.0).collect();
                return Err(fail(k, &format!("a field ({})", known.join(", "))));
            };
            k += 1;
            let value = |at: usize| -> Result<SqlValue, StoreError> {
                let Some(w) = words.get(at) else {
                    return Err(fail(at, "a value"));
                };
                if numeric {
                    w.text
                        .parse::<f64>()
                        .ok()
                        .filter(|v| v.is_finite() && !w.quoted)
                        .map(SqlValue::Real)
                        .ok_or_else(|| fail(at, &format!("a number for {name}")))
                } else {
                    Ok(SqlValue::Text(w.text.clone()))
                }
            };
            let op = words.get(k).map(|w| w.text.to_ascii_lowercase());
            match op.as_deref() {
                Some("between") => {
                    let low = value(k + 1)?;
                    if !words
                        .get(k + 2)
                        .is_some_and(|w| w.text.eq_ignore_ascii_case("and"))
                    {
                        return Err(fail(k + 2, "`and` of `between … and …`"));
                    }
                    let high = value(k + 3)?;
                    let n = first + params.len();
                    parts.push(format!("{name} BETWEEN ${n} AND ${}", n + 1));
                    params.push(low);
                    params.push(high);
                    k += 4;
                }
                Some(o @ ("=" | "!=" | "<>" | "<" | "<=" | ">" | ">=")) => {
                    let v = value(k + 1)?;
                    let o = if o == "!=" { "<>" } else { o };
                    parts.push(format!("{name} {o} ${}", first + params.len()));
                    params.push(v);
                    k += 2;
                }
                _ => return Err(fail(k, "an operator (= != < <= > >= between)")),
            }
            match words.get(k) {
                None => break,
                Some(w) if w.text.eq_ignore_ascii_case("and") && !w.quoted => k += 1,
                Some(_) => return Err(fail(k, "`and` or the end")),
            }
        }
        Ok(Condition {
            sql: parts.join(" AND "),
            params,
        })
    }
}

/// A word of a condition.
struct Word {
    text: String,
    quoted: bool,
}

/// Splits a condition into words: quoted strings, operators, the rest by spaces.
fn tokens(text: &str) -> Result<Vec<Word>, StoreError> {
    let mut out = Vec::new();
    let chars: Vec<char> = text.chars().collect();
    let mut k = 0;
    while k < chars.len() {
        let c = chars[k];
        if c.is_whitespace() {
            k += 1;
        } else if c == '\'' || c == '"' {
            let end = chars[k + 1..]
                .iter()
                .position(|&d| d == c)
                .ok_or_else(|| StoreError::Search(format!("in --where {text:?}: unclosed {c}")))?;
            out.push(Word {
                text: chars[k + 1..k + 1 + end].iter().collect(),
                quoted: true,
            });
            k += end + 2;
        } else if "<>=!".contains(c) {
            let two = chars
                .get(k + 1)
                .is_some_and(|&d| d == '=' || (c == '<' && d == '>'));
            let len = if two { 2 } else { 1 };
            out.push(Word {
                text: chars[k..k + len].iter().collect(),
                quoted: false,
            });
            k += len;
        } else {
            let start = k;
            while k < chars.len() && !chars[k].is_whitespace() && !"<>=!'\"".contains(chars[k]) {
                k += 1;
            }
            out.push(Word {
                text: chars[start..k].iter().collect(),
                quoted: false,
            });
        }
    }
    Ok(out)
}

fn hit(row: &[SqlValue], distance: Option<f64>) -> Hit {
    let text = |k: usize| row[k].text().unwrap_or_default().to_string();
    let real = |k: usize| row[k].real().unwrap_or(0.0);
    Hit {
        design: text(0),
        rev: row[1].int().unwrap_or(0),
        features: Features {
            tag: text(2),
            kind: text(3),
            head: text(4),
            material: text(5),
            od: real(6),
            length: real(7),
            pressure: real(8),
            temperature: real(9),
            nozzles: row[10].int().unwrap_or(0),
            max_nozzle: real(11),
            nozzle_total: real(12),
        },
        distance,
    }
}

impl Store {
    /// The `n` stored vessels nearest `like` by the distance above (nearest
    /// first, ties by design and tag), among those meeting `condition`.
    ///
    /// # Errors
    ///
    /// [`StoreError::Search`] for a bad condition, [`StoreError::Database`].
    pub fn search_like(
        &mut self,
        like: &Features,
        condition: Option<&str>,
        n: usize,
    ) -> Result<Vec<Hit>, StoreError> {
        let od = like.od.max(1.0);
        let length = like.length.max(1.0);
        let mut params: Vec<SqlValue> = vec![
            od.into(),
            length.into(),
            like.pressure.into(),
            like.pressure.max(100.0).into(),
            like.temperature.into(),
            like.kind.as_str().into(),
            like.head.as_str().into(),
            like.material.as_str().into(),
            like.nozzles.into(),
            like.max_nozzle.into(),
            like.max_nozzle.max(1.0).into(),
        ];
        let condition = condition.map(|c| Condition::parse(c, 12)).transpose()?;
        let mut filters = Vec::new();
        if let Some(c) = &condition {
            filters.push(c.sql.clone());
            params.extend(c.params.iter().cloned());
        }
        let limit = n as i64;
        // `(column, low, high)` conditions added to the query.
        let run =
            |store: &mut Store, ranges: &[(&str, f64, f64)]| -> Result<Vec<Hit>, StoreError> {
                let mut filters = filters.clone();
                let mut params = params.clone();
                for &(column, low, high) in ranges {
                    let k = params.len() + 1;
                    filters.push(format!("{column} BETWEEN ${k} AND ${}", k + 1));
                    params.push(low.into());
                    params.push(high.into());
                }
                let filter = if filters.is_empty() {
                    String::new()
                } else {
                    format!("WHERE {}", filters.join(" AND "))
                };
                let k = params.len() + 1;
                params.push(limit.into());
                let sql = format!(
                    "SELECT {COLUMNS}, {DISTANCE} AS distance FROM vessels {filter}
                 ORDER BY distance, design, tag LIMIT ${k}"
                );
                let rows = store.db.query(&sql, &params)?;
                Ok(rows.iter().map(|r| hit(r, r[13].real())).collect())
            };
        if n == 0 {
            return Ok(Vec::new());
        }
        let near = run(self, &[("od", od * (1.0 - NEAR), od * (1.0 + NEAR))])?;
        let radius = match near.last().and_then(|h| h.distance) {
            Some(r) if near.len() == n && r < 4.0 * NEAR => return Ok(near),
            Some(r) if near.len() == n => r * (1.0 + 1e-9) + 1e-12,
            _ => return run(self, &[]),
        };
        let p = like.pressure.max(100.0);
        let t = like.temperature;
        run(
            self,
            &[
                ("od", od * (1.0 - radius / 4.0), od * (1.0 + radius / 4.0)),
                (
                    "length",
                    length * (1.0 - radius / 2.0),
                    length * (1.0 + radius / 2.0),
                ),
                (
                    "pressure",
                    like.pressure - p * radius / 2.0,
                    like.pressure + p * radius / 2.0,
                ),
                ("temperature", t - 200.0 * radius, t + 200.0 * radius),
            ],
        )
    }

    /// The first `n` stored vessels meeting `condition`, by design and tag.
    ///
    /// # Errors
    ///
    /// [`StoreError::Search`] for a bad condition, [`StoreError::Database`].
    pub fn search_where(&mut self, condition: &str, n: usize) -> Result<Vec<Hit>, StoreError> {
        let c = Condition::parse(condition, 1)?;
        let mut params = c.params;
        let k = params.len() + 1;
        params.push((n as i64).into());
        let sql = format!(
            "SELECT {COLUMNS} FROM vessels WHERE {} ORDER BY design, tag LIMIT ${k}",
            c.sql
        );
        let rows = self.db.query(&sql, &params)?;
        Ok(rows.iter().map(|r| hit(r, None)).collect())
    }
}
