//! ASME B16.5 flange pressure–temperature ratings: the working pressure a flange
//! of a class and material group may carry at a temperature, interpolated
//! linearly between the table's temperatures (B16.5 para. 2.1 permits it), and
//! the check of a nozzle's flange against the pressure on its host at the design
//! temperature and against the vessel's hydrostatic test (the flange's shell test,
//! para. 2.6 / 8.2: 1.5 × its 38 °C rating).
//!
//! Shipped: Table 2-1.1 (Group 1.1: A105, A350 LF2, A216 WCB, A515-70, A516-70)
//! of ASME B16.5-2009/-2013 in bar, the same values B16.34-2013 Table 2-1.1 lists
//! for the standard class; Table 2-1.2 (Group 1.2: A216 WCC, A352 LCC/LC2/LC3,
//! A350 LF6 Cl. 2, A203 B/E) from −29 to 250 °C, the standard-class rows a valve
//! maker publishes from B16.34 (identical to B16.5's for the standard class),
//! cross-checked against B16.5-2003 Annex F Table F2-1.2 in psi (within 1.1 % at
//! 100, 200, 300 and 400 °F, the psi and bar tables being rounded separately);
//! Table 2-2.1 (Group 2.1: A182 F304, A240 304) from −29 to 300 °C as a public
//! data file reproduces it ([`SOURCE`]); and Tables 2-2.2 (Group 2.2: A182 F316,
//! A240 316) and 2-2.3 (Group 2.3: A182 F304L/F316L, A240 304L/316L) of the same
//! edition from −29 to 300 °C, the rows published alike by flange makers and by
//! public engineering tables (the 38 °C values are the well-known 275/720/1440/2160
//! psi of 316 and 230/600/1200/1800 psi of 316L). Both are checked against two
//! public copies on GitHub: a TypeScript B16.5 rating table (Groups 2.2 and 2.3,
//! every shipped value equal) and, independently, a Python valve-sizing module's
//! B16.34 CF8M rows (Group 2.2 at −29, 38 and 100 to 300 °C, equal). Above 300 °C
//! those three groups and every other group (1.3, …) are not shipped: their
//! flanges are reported as not rated, never guessed. Group 1.2 above 250 °C is
//! not shipped either: the public bar rows found stop there (the psi rows go on to
//! 900 °F, but B16.5 rates in bar separately and a conversion is not its table).
//!
//! Classes 1500 and 2500 of every shipped group are derived from its Class 300,
//! 600 and 900 rows by B16.5 Annex B's proportionality of rating to class
//! ([`DERIVATION`], [`rating_of_class`]), checked against the published Class
//! 1500 and 2500 rows of Groups 1.1 and 2.2. They rate a flange by its class
//! number; the modelled nozzle's [`FlangeClass`] stops at 900 because the flange
//! dimension tables do.

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

/// Group 1.2 working pressures, bar, Class 150, 300, 600, 900, at the first seven
/// [`TEMPERATURES`] (−29 to 250 °C): B16.34-2013 Table 2-1.2, standard class, as
/// published by reliaballvalve.com ("Valve Body Materials (ASME B16.34)
/// Pressure/temperature Ratings"), the same rows as B16.5 Table 2-1.2.
const GROUP_1_2: [[f64; 7]; 4] = [
    [19.8, 19.8, 19.5, 17.7, 15.8, 13.8, 12.1],
    [51.7, 51.7, 51.7, 51.5, 50.2, 48.6, 46.3],
    [103.4, 103.4, 103.4, 103.0, 100.3, 97.2, 92.7],
    [155.1, 155.1, 155.1, 154.6, 150.5, 145.8, 139.0],
];

/// Group 2.1 (304) working pressures, bar, Class 150, 300, 600, 900, at the first
/// eight [`TEMPERATURES`] (−29 to 300 °C): B16.5 Table 2-2.1 as a public data file
/// reproduces it (see [`SOURCE`]).
const GROUP_2_1: [[f64; 8]; 4] = [
    [19.0, 19.0, 18.3, 15.7, 14.2, 13.2, 12.1, 10.2],
    [49.6, 49.6, 47.8, 40.9, 37.0, 34.5, 32.5, 30.9],
    [99.3, 99.3, 95.6, 81.7, 74.0, 69.0, 65.0, 61.8],
    [148.9, 148.9, 143.5, 122.6, 111.0, 103.4, 97.5, 92.7],
];

/// Group 2.2 (316) working pressures, bar, Class 150, 300, 600, 900, at the first
/// eight [`TEMPERATURES`] (−29 to 300 °C).
const GROUP_2_2: [[f64; 8]; 4] = [
    [19.0, 19.0, 18.4, 16.2, 14.8, 13.7, 12.1, 10.2],
    [49.6, 49.6, 48.1, 42.2, 38.5, 35.7, 33.4, 31.6],
    [99.3, 99.3, 96.2, 84.4, 77.0, 71.3, 66.8, 63.2],
    [148.9, 148.9, 144.3, 126.6, 115.5, 107.0, 100.1, 94.9],
];

/// Group 2.3 (304L, 316L) working pressures, bar, as [`GROUP_2_2`].
const GROUP_2_3: [[f64; 8]; 4] = [
    [15.9, 15.9, 15.3, 13.3, 12.0, 11.2, 10.5, 10.0],
    [41.4, 41.4, 40.0, 34.8, 31.4, 29.2, 27.5, 26.1],
    [82.7, 82.7, 80.0, 69.6, 62.8, 58.3, 54.9, 52.1],
    [124.1, 124.1, 120.1, 104.4, 94.2, 87.5, 82.4, 78.2],
];

/// Where the shipped ratings come from.
pub const SOURCE: &str = "ASME B16.5-2009/-2013 Tables 2-1.1 (Group 1.1, −29 to 538 °C), \
    2-1.2 (Group 1.2, −29 to 250 °C), 2-2.1, 2-2.2 and 2-2.3 (Groups 2.1, 2.2 and 2.3, −29 \
    to 300 °C), standard class, bar; Table 2-1.1 identical to ASME B16.34-2013 Table 2-1.1 \
    as published by valve makers; Table 2-1.2 as reliaballvalve.com publishes B16.34-2013 \
    Table 2-1.2 (standard class, bar), cross-checked against B16.5-2003 Annex F Table \
    F2-1.2 (psi); Table 2-2.1 as a public flange-rating data file on GitHub reproduces it \
    (a TypeScript table stating B16.5-2020 Table 2-2.1, whose Group 1.1 rows equal the \
    Table 2-1.1 shipped here; the same file gives Group 1.2 the Group 1.1 values, which \
    B16.5 does not, so 1.2 is not taken from it); Classes 1500 and 2500 derived from \
    the Class 300, 600 and 900 rows by Annex B (DERIVATION)";

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
    a derived rating is never above what the published rows allow; checked against \
    the published Class 1500 and 2500 rows of Groups 1.1 (-29 to 538 C) and 2.2 \
    (-29 to 300 C), every entry within 0.25 bar and none more than 0.05 bar below \
    the derived value";

/// The rows of `group` for Classes 150, 300, 600, 900 and its table's name;
/// an error for a group whose table is not shipped.
fn rows(group: &str) -> Result<([&'static [f64]; 4], &'static str), CalcError> {
    fn four<const N: usize>(t: &'static [[f64; N]; 4]) -> [&'static [f64]; 4] {
        [&t[0], &t[1], &t[2], &t[3]]
    }
    Ok(match group {
        "1.1" => (four(&GROUP_1_1), "Table 2-1.1"),
        "1.2" => (four(&GROUP_1_2), "Table 2-1.2"),
        "2.1" => (four(&GROUP_2_1), "Table 2-2.1"),
        "2.2" => (four(&GROUP_2_2), "Table 2-2.2"),
        "2.3" => (four(&GROUP_2_3), "Table 2-2.3"),
        _ => {
            return Err(CalcError::Input {
                entity: format!("B16.5 group {group}"),
                field: "group".into(),
                value: f64::NAN,
                rule: "only the Group 1.1, 1.2, 2.1, 2.2 and 2.3 rating tables (Tables \
                       2-1.1, 2-1.2, 2-2.1, 2-2.2, 2-2.3) are shipped"
                    .into(),
            });
        }
    })
}

/// The rating in bar per unit of class number at the table's temperature index
/// `i`: the least value every published Class 300, 600 and 900 entry rounds from
/// (see [`DERIVATION`]).
fn per_class(rows: &[&[f64]; 4], i: usize) -> f64 {
    [(rows[1], 300.0), (rows[2], 600.0), (rows[3], 900.0)]
        .iter()
        .map(|(row, class)| (row[i] - 0.05) / class)
        .fold(f64::NEG_INFINITY, f64::max)
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
    let (rows, table) = rows(group)?;
    let Some(k) = CLASSES.iter().position(|&c| c == class) else {
        return Err(CalcError::Input {
            entity: format!("B16.5 group {group}"),
            field: "class".into(),
            value: f64::from(class),
            rule: "B16.5 standard classes are 150, 300, 600, 900, 1500 and 2500".into(),
        });
    };
    let n = rows[0].len();
    let temps = &TEMPERATURES[..n];
    let (first, last) = (temps[0], temps[n - 1]);
    if !(temperature.is_finite() && (first..=last).contains(&temperature)) {
        return Err(CalcError::Input {
            entity: format!("B16.5 group {group} class {class}"),
            field: "temperature".into(),
            value: temperature,
            rule: format!("{table} is shipped for {first} to {last} °C"),
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
