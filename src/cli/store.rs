//! `vesselcad store …`: the design store (see `vesselcad::store`) from the
//! command line — designs in and out, history, tags, differences and
//! similar-design search. The store is `--store PATH|URL`, else
//! `$VESSELCAD_STORE`, else `vesselcad.db` in the current folder; the author is
//! `--author`, else `$VESSELCAD_AUTHOR`, else `$USER`.
//!
//! Exit status: 0 done; 1 refused (an invalid design, unknown design, revision
//! or tag, a conflicting writer, a malformed search); 2 a file or the database
//! cannot be read or written.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, Subcommand};
use serde_json::json;
use vesselcad::design::units::to_inches;
use vesselcad::design::{self, Design, Units, to_canonical_json};
use vesselcad::store::{Change, Features, Hit, Revision, Store, StoreError, diff};

use super::fail;
use super::output::outln;

/// Arguments of `vesselcad store`.
#[derive(Args)]
pub struct StoreArgs {
    /// The store: a SQLite file, or a `postgres://user:password@host/db` URL
    /// (default: `$VESSELCAD_STORE`, else `vesselcad.db`).
    #[arg(long, global = true)]
    store: Option<String>,
    /// Who makes the change (default: `$VESSELCAD_AUTHOR`, else `$USER`).
    #[arg(long, global = true)]
    author: Option<String>,
    #[command(subcommand)]
    command: StoreCommand,
}

/// The store's subcommands.
#[derive(Subcommand)]
enum StoreCommand {
    /// Store a design file: a new design, or a new revision of a stored one.
    Import {
        /// The design file.
        design: PathBuf,
        /// The design's name in the store (default: the file name without `.json`).
        #[arg(long)]
        name: Option<String>,
        /// Why.
        #[arg(short, long, default_value = "import")]
        message: String,
    },
    /// The stored designs with their newest revision.
    List {
        /// As JSON.
        #[arg(long)]
        json: bool,
    },
    /// A design's revisions: number, time, author, tags, message.
    Log {
        /// The design's name.
        name: String,
        /// As JSON (with each revision's patch).
        #[arg(long)]
        json: bool,
    },
    /// One revision: who, when, why, its patch; `--design` prints its design.
    Show {
        /// The design's name.
        name: String,
        /// A revision number, a tag, or `head`.
        #[arg(default_value = "head")]
        rev: String,
        /// Print the design (canonical JSON, mm) instead.
        #[arg(long)]
        design: bool,
    },
    /// What changed between two revisions: the parameters, or the JSON Patch.
    Diff {
        /// The design's name.
        name: String,
        /// From this revision (number, tag or `head`).
        from: String,
        /// To this revision (default `head`).
        #[arg(default_value = "head")]
        to: String,
        /// Print the JSON Patch (RFC 6902) instead of the list.
        #[arg(long)]
        patch: bool,
    },
    /// Name a revision (`A`, `B`, `0`, …), as in the drawing's revision block.
    Tag {
        /// The design's name.
        name: String,
        /// The tag.
        tag: String,
        /// The revision (default `head`).
        #[arg(default_value = "head")]
        rev: String,
    },
    /// Make an earlier revision's design the newest, as a new revision (history
    /// is never rewritten).
    Checkout {
        /// The design's name.
        name: String,
        /// The revision to go back to (number, tag).
        rev: String,
        /// Why (default: `checkout <rev>`).
        #[arg(short, long)]
        message: Option<String>,
    },
    /// Write a revision's design to a file, in the unit it was imported in; a
    /// tagged revision carries its tag and date in every vessel's drawing
    /// revision block.
    Export {
        /// The design's name.
        name: String,
        /// The revision (default `head`).
        #[arg(default_value = "head")]
        rev: String,
        /// The file to write.
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Stored vessels like a design's vessel (ranked by distance), or meeting
    /// conditions (`--where "od between 2000 and 2600 and pressure >= 1000"`).
    Search {
        /// Rank by likeness to a vessel of this design file.
        #[arg(long)]
        like: Option<PathBuf>,
        /// Which vessel of `--like` (default: its first).
        #[arg(long)]
        vessel: Option<String>,
        /// Conditions on od, length, pressure, temperature, nozzles, max_nozzle,
        /// nozzle_total, kind, head, material, tag, design.
        #[arg(long = "where")]
        condition: Option<String>,
        /// How many.
        #[arg(short, default_value_t = 10)]
        n: usize,
        /// As JSON.
        #[arg(long)]
        json: bool,
    },
}

/// Runs `vesselcad store`.
pub fn run(args: StoreArgs) -> ExitCode {
    let author = args
        .author
        .or_else(|| std::env::var("VESSELCAD_AUTHOR").ok())
        .or_else(|| std::env::var("USER").ok())
        .unwrap_or_else(|| "unknown".into());
    let location = args
        .store
        .or_else(|| std::env::var("VESSELCAD_STORE").ok())
        .unwrap_or_else(|| "vesselcad.db".into());
    let mut store = match Store::open(&location) {
        Ok(s) => s,
        Err(e) => return store_failed(&e),
    };
    let outcome = match args.command {
        StoreCommand::Import {
            design,
            name,
            message,
        } => import(&mut store, &design, name, &author, message),
        StoreCommand::List { json } => list(&mut store, json),
        StoreCommand::Log { name, json } => log(&mut store, &name, json),
        StoreCommand::Show { name, rev, design } => show(&mut store, &name, &rev, design),
        StoreCommand::Diff {
            name,
            from,
            to,
            patch,
        } => diff_of(&mut store, &name, &from, &to, patch),
        StoreCommand::Tag { name, tag, rev } => store
            .resolve(&name, &rev)
            .and_then(|r| store.tag(&name, &tag, r).map(|()| r))
            .map(|r| {
                outln!("{name}: revision {r} tagged {tag}");
                ExitCode::SUCCESS
            }),
        StoreCommand::Checkout { name, rev, message } => {
            checkout(&mut store, &name, &rev, &author, message)
        }
        StoreCommand::Export { name, rev, output } => export(&mut store, &name, &rev, &output),
        StoreCommand::Search {
            like,
            vessel,
            condition,
            n,
            json,
        } => return search(&mut store, like.as_deref(), vessel, condition, n, json),
    };
    outcome.unwrap_or_else(|e| store_failed(&e))
}

/// Prints a store error; exit 2 for the database, 1 for a refusal.
fn store_failed(error: &StoreError) -> ExitCode {
    eprintln!("error: {error}");
    match error {
        StoreError::Database { .. }
        | StoreError::Disconnected { .. }
        | StoreError::NewerSchema { .. }
        | StoreError::Corrupt { .. } => ExitCode::from(2),
        _ => ExitCode::from(1),
    }
}

/// Reads a design file: the design in mm and the unit it was written in.
fn read_design(path: &Path) -> Result<(Design, Units), design::DesignError> {
    let bytes = design::read_design_bytes(path)?;
    let text = design::decode_design(path, &bytes)?;
    let units = design::parse_unchecked(text)?.units;
    Ok((design::parse(text)?, units))
}

fn import(
    store: &mut Store,
    path: &Path,
    name: Option<String>,
    author: &str,
    message: String,
) -> Result<ExitCode, StoreError> {
    let (design, units) = match read_design(path) {
        Ok(d) => d,
        Err(e) => return Ok(fail(&e)),
    };
    let name = name.unwrap_or_else(|| {
        let file = path.file_name().unwrap_or_default().to_string_lossy();
        file.strip_suffix(".json").unwrap_or(&file).to_string()
    });
    let change = Change {
        author: author.to_string(),
        message,
    };
    let before = store.head(&name)?;
    let revision = store.import(&name, &design, units, &change)?;
    if before == Some(revision.rev) {
        outln!("{name}: unchanged at revision {}", revision.rev);
    } else {
        outln!(
            "{name}: revision {} ({} vessel(s), {} change(s))",
            revision.rev,
            design.vessels.len(),
            revision.patch.as_array().map_or(0, Vec::len)
        );
    }
    Ok(ExitCode::SUCCESS)
}

fn list(store: &mut Store, as_json: bool) -> Result<ExitCode, StoreError> {
    let designs = store.designs()?;
    if as_json {
        let stats = store.stats()?;
        outln!("{}", json!({ "designs": designs, "stats": stats }));
        return Ok(ExitCode::SUCCESS);
    }
    for d in designs {
        outln!(
            "{}\trevision {}\t{} vessel(s)\t{}\t{}",
            d.name,
            d.head,
            d.vessels,
            d.at,
            d.author
        );
    }
    Ok(ExitCode::SUCCESS)
}

fn revision_line(r: &Revision) -> String {
    let tags = if r.tags.is_empty() {
        String::new()
    } else {
        format!(" [{}]", r.tags.join(", "))
    };
    format!("{}{tags}\t{}\t{}\t{}", r.rev, r.at, r.author, r.message)
}

fn log(store: &mut Store, name: &str, as_json: bool) -> Result<ExitCode, StoreError> {
    let revisions = store.log(name)?;
    if as_json {
        outln!("{}", json!({ "design": name, "revisions": revisions }));
        return Ok(ExitCode::SUCCESS);
    }
    for r in revisions.iter().rev() {
        outln!("{}", revision_line(r));
    }
    Ok(ExitCode::SUCCESS)
}

fn show(store: &mut Store, name: &str, rev: &str, design: bool) -> Result<ExitCode, StoreError> {
    let rev = store.resolve(name, rev)?;
    if design {
        let d = store.design_at(name, rev)?;
        super::output::out!("{}", to_canonical_json(&d));
        return Ok(ExitCode::SUCCESS);
    }
    let r = store.revision(name, rev)?;
    outln!("{}", revision_line(&r));
    outln!("hash {}", r.hash);
    outln!(
        "{}",
        serde_json::to_string_pretty(&r.patch).unwrap_or_default()
    );
    Ok(ExitCode::SUCCESS)
}

fn diff_of(
    store: &mut Store,
    name: &str,
    from: &str,
    to: &str,
    as_patch: bool,
) -> Result<ExitCode, StoreError> {
    let (from, to) = (store.resolve(name, from)?, store.resolve(name, to)?);
    let before = store.design_at(name, from)?;
    let after = store.design_at(name, to)?;
    let (patch, changes) = diff(&before, &after);
    if as_patch {
        outln!(
            "{}",
            serde_json::to_string_pretty(&patch).unwrap_or_default()
        );
        return Ok(ExitCode::SUCCESS);
    }
    if changes.is_empty() {
        outln!("{name}: revisions {from} and {to} are the same design");
    }
    for c in changes {
        outln!("{c}");
    }
    Ok(ExitCode::SUCCESS)
}

fn checkout(
    store: &mut Store,
    name: &str,
    rev: &str,
    author: &str,
    message: Option<String>,
) -> Result<ExitCode, StoreError> {
    let target = store.resolve(name, rev)?;
    let head = store.head(name)?.unwrap_or(0);
    let wanted = store.design_at(name, target)?;
    let current = store.design_at(name, head)?;
    let change = Change {
        author: author.to_string(),
        message: message.unwrap_or_else(|| format!("checkout {rev}")),
    };
    let r = store.commit(name, head, &current, &wanted, &change)?;
    outln!(
        "{name}: revision {} holds the design of revision {target}",
        r.rev
    );
    Ok(ExitCode::SUCCESS)
}

fn export(store: &mut Store, name: &str, rev: &str, output: &Path) -> Result<ExitCode, StoreError> {
    let rev = store.resolve(name, rev)?;
    let mut d = store.design_at(name, rev)?;
    // A named revision is an issue of the drawings: its newest tag and its date
    // fill every vessel's revision block (a tag longer than the block's 8
    // characters is left out, and said so).
    if let Some(issued) = store.log(name)?.into_iter().find(|r| r.rev == rev)
        && let Some(tag) = issued.tags.last()
    {
        if tag.chars().count() <= MAX_DRAWING_REVISION {
            for v in &mut d.vessels {
                v.drawing.revision = Some(tag.clone());
                v.drawing.date = issued.at.get(..10).map(str::to_string);
            }
        } else {
            outln!(
                "{name}: tag {tag} is longer than a drawing's revision ({MAX_DRAWING_REVISION} characters): the revision blocks are left as stored"
            );
        }
    }
    if store.units(name)? == Units::In {
        to_inches(&mut d);
    }
    if let Err(e) = design::save(&d, output) {
        return Ok(fail(&e));
    }
    outln!("{name}: revision {rev} written to {}", output.display());
    Ok(ExitCode::SUCCESS)
}

/// The longest revision a drawing's title block takes (`drawing.revision`).
const MAX_DRAWING_REVISION: usize = 8;

fn search(
    store: &mut Store,
    like: Option<&Path>,
    vessel: Option<String>,
    condition: Option<String>,
    n: usize,
    as_json: bool,
) -> ExitCode {
    let hits = match like {
        Some(path) => {
            let design = match design::load(path) {
                Ok(d) => d,
                Err(e) => return fail(&e),
            };
            let chosen = match &vessel {
                Some(tag) => design.vessels.iter().find(|v| &v.tag == tag),
                None => design.vessels.first(),
            };
            let Some(chosen) = chosen else {
                eprintln!(
                    "error: {}: no vessel {}",
                    path.display(),
                    vessel.map_or("at all".into(), |t| format!("has the tag {t:?}"))
                );
                return ExitCode::from(1);
            };
            store.search_like(&Features::of(chosen), condition.as_deref(), n)
        }
        None => match &condition {
            Some(c) => store.search_where(c, n),
            None => {
                eprintln!("error: store search needs --like <design.json> or --where <conditions>");
                return ExitCode::from(2);
            }
        },
    };
    let hits: Vec<Hit> = match hits {
        Ok(h) => h,
        Err(e) => return store_failed(&e),
    };
    if as_json {
        outln!("{}", json!({ "hits": hits }));
        return ExitCode::SUCCESS;
    }
    for h in hits {
        let f = &h.features;
        let distance = h.distance.map_or(String::new(), |d| format!("{d:.3}\t"));
        outln!(
            "{distance}{}/{}\t{} {} OD {} L {} p {} kPa T {} °C {} nozzle(s) {}",
            h.design,
            f.tag,
            f.kind,
            f.head,
            f.od,
            f.length,
            f.pressure,
            f.temperature,
            f.nozzles,
            f.material
        );
    }
    ExitCode::SUCCESS
}
