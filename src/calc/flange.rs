//! ASME B16.5 flange pressure–temperature ratings: the working pressure a flange
//! of a class and material group may carry at a temperature, interpolated
//! linearly between the table's temperatures (B16.5 para. 2.1 permits it), and
//! the check of a nozzle's flange against the pressure on its host at the design
//! temperature and against the vessel's hydrostatic test (the flange's shell test,
//! para. 2.6 / 8.2: 1.5 × its 38 °C rating).
//!
//! Shipped, Classes 150 to 900 in bar from ASME B16.5-2009/-2013: Table 2-1.1
//! (Group 1.1: A105, A350 LF2, A216 WCB, A515-70, A516-70), the same values
//! B16.34-2013 Table 2-1.1 lists for the standard class; Table 2-1.2 (Group 1.2:
//! A216 WCC, A352 LCC/LC2/LC3, A350 LF6 Cl. 2, A203 B/E); Table 2-1.4 (Group 1.4:
//! A350 LF1 Cl. 1, A515-60, A516-60); Table 2-2.1 (Group 2.1:
//! A182 F304, A240 304) and Table 2-2.2 (Group 2.2: A182 F316, A240 316), all
//! five from −29 to 538 °C (Class 150's last entry); Table 2-2.3 (Group 2.3: A182
//! F304L/F316L, A240 304L/316L) from −29 to 450 °C, the end of its table. Each
//! row is checked against two public copies where two were found ([`SOURCE`]): a
//! JavaScript flange-rating calculator on GitHub carrying every B16.5-2009 table
//! and, independently, Group 1.1 and 1.2 to 250 °C as a valve maker publishes
//! B16.34 (1.2 also against B16.5-2003 Annex F in psi, within 1.1 % at 100 to
//! 400 °F), Group 2.1 as a TypeScript B16.5-2020 table (every entry equal),
//! Group 2.2 as that TypeScript table (to 450 °C) and a Python valve-sizing
//! module's B16.34 CF8M rows (to 538 °C), Group 2.3 as the TypeScript table at
//! 350, 400 and 450 °C. The copies agree on every shared entry but Group 2.2 at
//! 538 °C, Classes 600 and 900, where the B16.34 copy prints 50.4 and 75.6 bar and
//! the B16.5 copy 50.0 and 75.2: the lower is shipped. Group 1.2 above 300 °C and
//! Group 2.3 at 325, 375 and 425 °C and the whole of Group 1.4 rest on the
//! calculator alone (Group 1.4's Classes 300 to 2500 are proportional to one value
//! per temperature within B16.5's rounding, and its Class 150 from 200 °C equals
//! Group 1.1's, as the Class 150 ceiling makes every Group 1.x row). Other groups
//! (1.3, …) are not shipped: their flanges are reported as not rated, never
//! guessed.
//!
//! Classes 1500 and 2500 of every shipped group are derived from its Class 300,
//! 600 and 900 rows by B16.5 Annex B's proportionality of rating to class
//! ([`DERIVATION`], [`rating_of_class`]), checked against the published Class
//! 1500 and 2500 rows of every shipped group; Group 2.2's stop at 475 °C, above
//! which B16.5's ceiling pressures hold its published Class 1500 and 2500 rows
//! below the proportional values. They rate a flange by its class number; the
//! modelled nozzle's [`FlangeClass`] stops at 900 because the flange dimension
//! tables do.

use serde::Serialize;

use super::CalcError;
use crate::parts::tables::FlangeClass;

/// Temperatures of B16.5 Table 2-1.1, °C (the first row is "−29 to 38").
const TEMPERATURES: [f64; 17] = [
    -29.0, 38.0, 50.0, 100.0, 150.0, 200.0, 250.0, 300.0, 325.0, 350.0, 375.0, 400.0, 425.0, 450.0,
    475.0, 500.0, 538.0,
];

/// Group 1.1 working pressures, bar, for Class 150, 300, 600 and 900, at
/// [`TEMPERATURES`] (the "−29 to 38" value repeated at both ends of its row).
const GROUP_1_1: [[f64; 17]; 4] = [
    [
        19.6, 19.6, 19.2, 17.7, 15.8, 13.8, 12.1, 10.2, 9.3, 8.4, 7.4, 6.5, 5.5, 4.6, 3.7, 2.8, 1.4,
    ],
    [
        51.1, 51.1, 50.1, 46.6, 45.1, 43.8, 41.9, 39.8, 38.7, 37.6, 36.4, 34.7, 28.8, 23.0, 17.4,
        11.8, 5.9,
    ],
    [
        102.1, 102.1, 100.2, 93.2, 90.2, 87.6, 83.9, 79.6, 77.4, 75.1, 72.7, 69.4, 57.5, 46.0,
        34.9, 23.5, 11.8,
    ],
    [
        153.2, 153.2, 150.4, 139.8, 135.2, 131.4, 125.8, 119.5, 116.1, 112.7, 109.1, 104.2, 86.3,
        69.0, 52.3, 35.3, 17.7,
    ],
];

/// Group 1.2 working pressures, bar, Class 150, 300, 600, 900, at
/// [`TEMPERATURES`]: B16.5-2009 Table 2-1.2 as a public flange-rating calculator
/// reproduces it (see [`SOURCE`]); to 250 °C also as reliaballvalve.com
/// publishes B16.34-2013 Table 2-1.2 (standard class, the same rows).
const GROUP_1_2: [[f64; 17]; 4] = [
    [
        19.8, 19.8, 19.5, 17.7, 15.8, 13.8, 12.1, 10.2, 9.3, 8.4, 7.4, 6.5, 5.5, 4.6, 3.7, 2.8, 1.4,
    ],
    [
        51.7, 51.7, 51.7, 51.5, 50.2, 48.6, 46.3, 42.9, 41.4, 40.0, 37.8, 34.7, 28.8, 23.0, 17.1,
        11.6, 5.9,
    ],
    [
        103.4, 103.4, 103.4, 103.0, 100.3, 97.2, 92.7, 85.7, 82.6, 80.0, 75.7, 69.4, 57.5, 46.0,
        34.2, 23.2, 11.8,
    ],
    [
        155.1, 155.1, 155.1, 154.6, 150.5, 145.8, 139.0, 128.6, 124.0, 120.1, 113.5, 104.2, 86.3,
        69.0, 51.3, 34.7, 17.7,
    ],
];

/// Group 1.4 (A350 LF1 Cl. 1, A515-60, A516-60) working pressures, bar, Class
/// 150, 300, 600, 900, at [`TEMPERATURES`]: B16.5 Table 2-1.4 as the JavaScript
/// calculator of [`SOURCE`] reproduces it (one copy; see [`SOURCE`]).
const GROUP_1_4: [[f64; 17]; 4] = [
    [
        16.3, 16.3, 16.0, 14.9, 14.4, 13.8, 12.1, 10.2, 9.3, 8.4, 7.4, 6.5, 5.5, 4.6, 3.7, 2.8, 1.4,
    ],
    [
        42.6, 42.6, 41.8, 38.8, 37.6, 36.4, 34.9, 33.2, 32.2, 31.2, 30.4, 29.3, 25.8, 21.4, 14.1,
        10.3, 5.9,
    ],
    [
        85.1, 85.1, 83.5, 77.7, 75.1, 72.8, 69.8, 66.4, 64.5, 62.5, 60.7, 58.7, 51.5, 42.7, 28.2,
        20.6, 11.8,
    ],
    [
        127.7, 127.7, 125.3, 116.5, 112.7, 109.2, 104.7, 99.5, 96.7, 93.7, 91.1, 88.0, 77.3, 64.1,
        42.3, 30.9, 17.7,
    ],
];

/// Group 2.1 (304) working pressures, bar, Class 150, 300, 600, 900, at
/// [`TEMPERATURES`]: B16.5 Table 2-2.1 as two public data files reproduce it
/// (see [`SOURCE`]).
const GROUP_2_1: [[f64; 17]; 4] = [
    [
        19.0, 19.0, 18.3, 15.7, 14.2, 13.2, 12.1, 10.2, 9.3, 8.4, 7.4, 6.5, 5.5, 4.6, 3.7, 2.8, 1.4,
    ],
    [
        49.6, 49.6, 47.8, 40.9, 37.0, 34.5, 32.5, 30.9, 30.2, 29.6, 29.0, 28.4, 28.0, 27.4, 26.9,
        26.5, 24.4,
    ],
    [
        99.3, 99.3, 95.6, 81.7, 74.0, 69.0, 65.0, 61.8, 60.4, 59.3, 58.1, 56.9, 56.0, 54.8, 53.9,
        53.0, 48.9,
    ],
    [
        148.9, 148.9, 143.5, 122.6, 111.0, 103.4, 97.5, 92.7, 90.7, 88.9, 87.1, 85.3, 84.0, 82.2,
        80.8, 79.5, 73.3,
    ],
];

/// Group 2.2 (316) working pressures, bar, Class 150, 300, 600, 900, at
/// [`TEMPERATURES`].
const GROUP_2_2: [[f64; 17]; 4] = [
    [
        19.0, 19.0, 18.4, 16.2, 14.8, 13.7, 12.1, 10.2, 9.3, 8.4, 7.4, 6.5, 5.5, 4.6, 3.7, 2.8, 1.4,
    ],
    [
        49.6, 49.6, 48.1, 42.2, 38.5, 35.7, 33.4, 31.6, 30.9, 30.3, 29.9, 29.4, 29.1, 28.8, 28.7,
        28.2, 25.2,
    ],
    [
        99.3, 99.3, 96.2, 84.4, 77.0, 71.3, 66.8, 63.2, 61.8, 60.7, 59.8, 58.9, 58.3, 57.7, 57.3,
        56.5, 50.0,
    ],
    [
        148.9, 148.9, 144.3, 126.6, 115.5, 107.0, 100.1, 94.9, 92.7, 91.0, 89.6, 88.3, 87.4, 86.5,
        86.0, 84.7, 75.2,
    ],
];

/// Group 2.3 (304L, 316L) working pressures, bar, Class 150, 300, 600, 900, at
/// the first fourteen [`TEMPERATURES`] (−29 to 450 °C, the end of Table 2-2.3).
const GROUP_2_3: [[f64; 14]; 4] = [
    [
        15.9, 15.9, 15.3, 13.3, 12.0, 11.2, 10.5, 10.0, 9.3, 8.4, 7.4, 6.5, 5.5, 4.6,
    ],
    [
        41.4, 41.4, 40.0, 34.8, 31.4, 29.2, 27.5, 26.1, 25.5, 25.1, 24.8, 24.3, 23.9, 23.4,
    ],
    [
        82.7, 82.7, 80.0, 69.6, 62.8, 58.3, 54.9, 52.1, 51.0, 50.1, 49.5, 48.6, 47.7, 46.8,
    ],
    [
        124.1, 124.1, 120.1, 104.4, 94.2, 87.5, 82.4, 78.2, 76.4, 75.2, 74.3, 72.9, 71.6, 70.2,
    ],
];

/// Where the shipped ratings come from.
pub const SOURCE: &str = "ASME B16.5-2009/-2013 Tables 2-1.1, 2-1.2, 2-1.4, 2-2.1 and \
    2-2.2 (Groups 1.1, 1.2, 1.4, 2.1, 2.2, −29 to 538 °C) and 2-2.3 (Group 2.3, −29 to 450 °C), \
    standard class, bar. Every table as a public JavaScript B16.5 flange-rating \
    calculator on GitHub carries it (all B16.5-2009 tables, Classes 150 to 2500, −29 \
    to 816 °C). Checked against: Table 2-1.1 as published by valve makers for \
    B16.34-2013 Table 2-1.1; Table 2-1.2 to 250 °C as reliaballvalve.com publishes \
    B16.34-2013 Table 2-1.2 (standard class), and against B16.5-2003 Annex F Table \
    F2-1.2 (psi) to 400 °F; Table 2-2.1 as a TypeScript table on GitHub stating \
    B16.5-2020 Table 2-2.1 (every entry equal; the same file gives Group 1.2 the \
    Group 1.1 values, which B16.5 does not, so 1.2 is not checked against it); \
    Tables 2-2.2 and 2-2.3 as a second TypeScript table reproduces them (2.2 to \
    450 °C, 2.3 at 350, 400, 450 °C) and Table 2-2.2 as a Python valve-sizing module \
    reproduces B16.34 CF8M (to 538 °C; at 538 °C it prints Classes 600 and 900 as \
    50.4 and 75.6 bar against the B16.5 copy's 50.0 and 75.2, the lower shipped). \
    Table 2-1.4 from the calculator alone (no second copy found). Classes 1500 and \
    2500 derived from the Class 300, 600 and 900 rows by Annex B (DERIVATION)";

/// The class's number, e.g. 150.
pub fn class_number(class: FlangeClass) -> u32 {
    match class {
        FlangeClass::C150 => 150,
        FlangeClass::C300 => 300,
        FlangeClass::C600 => 600,
        FlangeClass::C900 => 900,
    }
}

/// The B16.5 standard classes this module rates: the four shipped as rows and
/// the two derived from them ([`DERIVED_CLASSES`]).
pub const CLASSES: [u32; 6] = [150, 300, 600, 900, 1500, 2500];

/// Classes 1500 and 2500: not shipped as rows but derived from the Class 300,
/// 600 and 900 rows by B16.5 Annex B (see [`DERIVATION`]).
pub const DERIVED_CLASSES: [u32; 2] = [1500, 2500];

/// How Classes 1500 and 2500 are rated.
pub const DERIVATION: &str = "ASME B16.5 Annex B rates every standard class from \
    Class 300 up as p = Pr S1 / 8750, limited by the ceiling pressure Pc, with Pr the \
    class number and S1 and Pc the same for every class but for Pc's proportionality \
    to Pr: each class's rating at a temperature is the class number times one value \
    of that temperature, rounded to 0.1 bar in the table. Classes 1500 and 2500 are \
    that value times 1500 and 2500, the value taken as the least one that every \
    published Class 300, 600 and 900 entry of the row rounds from (the low end of the \
    intersection of [(p - 0.05)/class, (p + 0.05)/class] over the three classes), so \
    a derived rating is never above what the published rows allow; where the three \
    rows do not round from one value (their rounding, or a ceiling), the most the \
    lowest of them allows (the high end's least). Checked against the published \
    Class 1500 and 2500 rows of every shipped group (the JavaScript copy of SOURCE): \
    Groups 1.1, 2.1, 2.2 (to 475 C) and 2.3 from 0.05 bar below to 0.25 bar above the \
    derived value, Group 1.2 from 0.08 below to 0.54 above, Group 1.4 from 0.02 to \
    0.31 above; Group 2.2 from 500 C is \
    held below the proportional values by B16.5's ceiling pressures (140.9 / 235.0 \
    bar at 500 C), so its derived classes stop at 475 C";

/// The rows of one group for Classes 150, 300, 600 and 900, their temperatures
/// (°C) and the table's name.
type Rows = ([&'static [f64]; 4], &'static [f64], &'static str);

/// The rows of `group`; an error for a group whose table is not shipped.
fn rows(group: &str) -> Result<Rows, CalcError> {
    fn four<const N: usize>(t: &'static [[f64; N]; 4]) -> [&'static [f64]; 4] {
        [&t[0], &t[1], &t[2], &t[3]]
    }
    Ok(match group {
        "1.1" => (four(&GROUP_1_1), &TEMPERATURES, "Table 2-1.1"),
        "1.2" => (four(&GROUP_1_2), &TEMPERATURES, "Table 2-1.2"),
        "1.4" => (four(&GROUP_1_4), &TEMPERATURES, "Table 2-1.4"),
        "2.1" => (four(&GROUP_2_1), &TEMPERATURES, "Table 2-2.1"),
        "2.2" => (four(&GROUP_2_2), &TEMPERATURES, "Table 2-2.2"),
        "2.3" => (four(&GROUP_2_3), &TEMPERATURES[..14], "Table 2-2.3"),
        _ => {
            return Err(CalcError::Input {
                entity: format!("B16.5 group {group}"),
                field: "group".into(),
                value: f64::NAN,
                rule: "only the Group 1.1, 1.2, 1.4, 2.1, 2.2 and 2.3 rating tables \
                       (Tables 2-1.1, 2-1.2, 2-1.4, 2-2.1, 2-2.2, 2-2.3) are shipped"
                    .into(),
            });
        }
    })
}

/// The rating in bar per unit of class number at the table's temperature index
/// `i`: the least value every published Class 300, 600 and 900 entry rounds from,
/// or, where the three rows do not round from one value, the most any of them
/// allows (see [`DERIVATION`]).
fn per_class(rows: &[&[f64]; 4], i: usize) -> f64 {
    let classes = [(rows[1], 300.0), (rows[2], 600.0), (rows[3], 900.0)];
    let least = classes
        .iter()
        .map(|(row, class)| (row[i] - 0.05) / class)
        .fold(f64::NEG_INFINITY, f64::max);
    let most = classes
        .iter()
        .map(|(row, class)| (row[i] + 0.05) / class)
        .fold(f64::INFINITY, f64::min);
    least.min(most)
}

/// The highest temperature, °C, the derived Classes 1500 and 2500 of `group`
/// are given for: Group 2.2's published Class 1500 and 2500 entries from 500 °C
/// (140.9 / 235.0 bar at 500 °C, 125.5 / 208.9 at 538 °C) sit below the values
/// proportional to its lower classes (B16.5's ceiling pressures govern there), so
/// its derivation stops at 475 °C; every other shipped group's derivation meets
/// its published Class 1500 and 2500 rows to the table's end.
fn derived_to(group: &str) -> f64 {
    match group {
        "2.2" => 475.0,
        _ => f64::INFINITY,
    }
}

/// The B16.5 rating of a flange of `class` in material `group` (e.g. `"1.1"`) at
/// `temperature` °C, MPa gauge; an error for a group whose table is not shipped
/// or a temperature outside the shipped rows of its table.
pub fn rating(group: &str, class: FlangeClass, temperature: f64) -> Result<f64, CalcError> {
    rating_of_class(group, class_number(class), temperature)
}

/// The B16.5 rating of a Class `class` flange (150, 300, 600, 900, 1500 or 2500)
/// in material `group` at `temperature` °C, MPa gauge: Classes 150 to 900 from
/// the shipped rows, 1500 and 2500 derived from them ([`DERIVATION`]); linear
/// between the table's temperatures. An error for another class, a group whose
/// table is not shipped, or a temperature outside its table's shipped rows.
pub fn rating_of_class(group: &str, class: u32, temperature: f64) -> Result<f64, CalcError> {
    let (rows, temps, table) = rows(group)?;
    let Some(k) = CLASSES.iter().position(|&c| c == class) else {
        return Err(CalcError::Input {
            entity: format!("B16.5 group {group}"),
            field: "class".into(),
            value: f64::from(class),
            rule: "B16.5 standard classes are 150, 300, 600, 900, 1500 and 2500".into(),
        });
    };
    let n = temps.len();
    let (first, last) = (temps[0], temps[n - 1]);
    if !(temperature.is_finite() && (first..=last).contains(&temperature)) {
        return Err(CalcError::Input {
            entity: format!("B16.5 group {group} class {class}"),
            field: "temperature".into(),
            value: temperature,
            rule: format!("{table} is shipped for {first} to {last} °C"),
        });
    }
    if k >= rows.len() && temperature > derived_to(group) {
        return Err(CalcError::Input {
            entity: format!("B16.5 group {group} class {class}"),
            field: "temperature".into(),
            value: temperature,
            rule: format!(
                "Classes 1500 and 2500 of {table} are derived (Annex B) to {} °C only: above it \
                 B16.5's ceiling pressures govern them",
                derived_to(group)
            ),
        });
    }
    let at = |i: usize| match rows.get(k) {
        Some(row) => row[i],
        None => f64::from(class) * per_class(&rows, i),
    };
    let i = temps
        .windows(2)
        .position(|w| temperature <= w[1])
        .unwrap_or(n - 2);
    let (t0, t1) = (temps[i], temps[i + 1]);
    let bar = at(i) + (temperature - t0) / (t1 - t0) * (at(i + 1) - at(i));
    Ok(bar * 0.1)
}

/// A nozzle flange's rating check.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FlangeRating {
    /// Class, e.g. 150.
    pub class: u32,
    /// B16.5 material group, e.g. `1.1`.
    pub group: String,
    /// Design temperature, °C.
    pub temperature: f64,
    /// Rating at the design temperature, MPa.
    pub rating: f64,
    /// Pressure on the flange: the host's design pressure with static head, MPa.
    pub pressure: f64,
    /// The flange's shell-test limit, 1.5 × its 38 °C rating, MPa (the vessel's
    /// hydrotest at the top must not exceed it; checked with the vessel's figures).
    pub test_limit: f64,
    /// Why the flange fails at design conditions, when it does.
    pub deficiency: Option<String>,
}

/// Checks the flange of nozzle `mark`, of `class` and `group`, under `pressure`
/// MPa at `temperature` °C.
pub fn flange_rating(
    mark: &str,
    class: FlangeClass,
    group: &str,
    pressure: f64,
    temperature: f64,
) -> Result<FlangeRating, CalcError> {
    let at = rating(group, class, temperature)?;
    let test_limit = 1.5 * rating(group, class, 38.0)?;
    let n = class_number(class);
    let deficiency = (pressure > at).then(|| {
        format!(
            "{mark}: B16.5 Class {n} (group {group}) is rated {at:.3} MPa at {temperature} °C, \
             below the {pressure:.3} MPa on it"
        )
    });
    Ok(FlangeRating {
        class: n,
        group: group.to_string(),
        temperature,
        rating: at,
        pressure,
        test_limit,
        deficiency,
    })
}
