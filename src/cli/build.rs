//! `vesselcad build`: a design built (in chunks, with a progress bar on a
//! terminal) and streamed as binary glTF to a file or standard output.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Instant;

use clap::{Args, ValueEnum};
use vesselcad::design::{Design, load};
use vesselcad::export::{
    Compression, ExportError, GlbOptions, Granularity, Normals, Scene, TilesWriter, merge_scene,
    quantization_budget, stream_glb_with, stream_glb_with_to, write_glb_with, write_tiles,
};
use vesselcad::fab::scene_levels::annotate_scene;
use vesselcad::fab::seam_glb::{add_seams, seam_lines};
use vesselcad::fab::{ProcessPlan, ShopRules};
use vesselcad::mesh::{
    DEFAULT_VERTEX_BUDGET, MAX_VERTEX_BUDGET, MIN_VERTEX_BUDGET, TessellationOptions,
};
use vesselcad::model::{Model, ModelError};
use vesselcad::plant::build_plant;

use super::output::{is_broken_pipe, outln};
use super::progress::bar;
use super::{fail, model_error};

/// Arguments of `vesselcad build`.
#[derive(Args)]
pub struct BuildArgs {
    /// The design file (JSON, vesselcad/1).
    design: PathBuf,
    /// Output GLB file (`.glb`), or `-` for standard output.
    #[arg(short, long, required_unless_present = "tiles")]
    output: Option<PathBuf>,
    /// Write 3D Tiles 1.1 into this directory instead: one GLB per vessel and
    /// a `tileset.json` (plant frame, metres, Z-up).
    #[arg(long, conflicts_with = "output")]
    tiles: Option<PathBuf>,
    /// With `--tiles`: levels of detail, their chordal tolerances in mm from
    /// coarse to fine (e.g. `5,1,0.2`): each vessel is meshed at each and
    /// written as one GLB per level, each finer level a `REPLACE` child tile
    /// of the coarser one. Instead of `--tolerance`.
    #[arg(long, value_delimiter = ',', num_args = 1.., requires = "tiles",
          conflicts_with = "tolerance", allow_negative_numbers = true)]
    lod: Vec<f64>,
    /// Chordal tolerance of the meshes, mm.
    #[arg(long, default_value_t = TessellationOptions::DEFAULT.tolerance, allow_negative_numbers = true)]
    tolerance: f64,
    /// Largest ratio between a triangle's sizes in two directions (≥ 1; e.g. 3
    /// for analysis-quality triangles). No limit by default.
    #[arg(long, allow_negative_numbers = true)]
    max_stretch: Option<f64>,
    /// Most vertices the mesher may give one patch (1000 to 4294967295): a
    /// patch that needs more is refused, naming it, instead of taking the
    /// memory and time it would need.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_VERTEX_BUDGET as u64,
          value_parser = clap::value_parser!(u64).range(MIN_VERTEX_BUDGET as u64..=MAX_VERTEX_BUDGET as u64))]
    max_vertices: u64,
    /// Quantize (`KHR_mesh_quantization`): 16-bit positions and 8-bit normals,
    /// with a quarter of the tolerance given to quantization (meshes are made
    /// to 0.75 × the tolerance, so the file holds the tolerance).
    #[arg(long)]
    quantize: bool,
    /// Compress the buffer: `meshopt` (`EXT_meshopt_compression`).
    #[arg(long, value_enum)]
    compress: Option<CompressArg>,
    /// Vertex normals: `smooth` (default: a unit normal per vertex, smooth
    /// shading) or `flat` (none written; viewers compute flat normals, so
    /// curved surfaces show their facets — the smallest file).
    #[arg(long, value_enum, default_value = "smooth")]
    normals: NormalsArg,
    /// Write every patch's mesh on its own, even where patches share one.
    #[arg(long)]
    no_reuse: bool,
    /// Draw the patches that share a mesh with one instanced node each
    /// (`EXT_mesh_gpu_instancing`, one draw call per shared mesh; their ids in
    /// the node's extras). Without it, a plain node per patch, which every
    /// viewer reads.
    #[arg(long, conflicts_with = "no_reuse")]
    instancing: bool,
    /// What one mesh (one draw call per material) holds: `patch` (default),
    /// `part`, `vessel` or `plant`; merged meshes keep the tolerance.
    #[arg(long, value_enum, default_value = "patch")]
    granularity: GranularityArg,
    /// Add fabrication data from each vessel's process plan (built-in shop
    /// rules): `fab: {level, operations}` in the extras of part and nozzle
    /// nodes, and the seams as line nodes under each vessel.
    #[arg(long, conflicts_with = "tiles")]
    fab: bool,
}

/// Granularities of `--granularity`.
#[derive(Clone, Copy, ValueEnum)]
enum GranularityArg {
    /// One mesh per patch.
    Patch,
    /// One mesh per part or nozzle.
    Part,
    /// One mesh per vessel and material.
    Vessel,
    /// One mesh per material for the whole plant.
    Plant,
}

impl From<GranularityArg> for Granularity {
    fn from(g: GranularityArg) -> Self {
        match g {
            GranularityArg::Patch => Granularity::Patch,
            GranularityArg::Part => Granularity::Part,
            GranularityArg::Vessel => Granularity::Vessel,
            GranularityArg::Plant => Granularity::Plant,
        }
    }
}

/// Vertex normals of `--normals`.
#[derive(Clone, Copy, ValueEnum)]
enum NormalsArg {
    /// A unit normal per vertex.
    Smooth,
    /// None: the viewer shades flat.
    Flat,
}

/// Compressions of `--compress`.
#[derive(Clone, Copy, ValueEnum)]
enum CompressArg {
    /// `EXT_meshopt_compression`.
    Meshopt,
}

/// Runs `vesselcad build`.
pub fn run(args: BuildArgs) -> ExitCode {
    let BuildArgs {
        design,
        output,
        tolerance,
        max_stretch,
        max_vertices,
        quantize,
        compress,
        normals,
        no_reuse,
        instancing,
        granularity,
        tiles,
        lod,
        fab,
    } = args;
    if tiles.is_none() && !lod.is_empty() {
        eprintln!(
            "error: --lod needs --tiles DIR: levels of detail are written as a 3D Tiles \
             tileset, one GLB per vessel and level"
        );
        return ExitCode::from(2);
    }
    let output = output.unwrap_or_default();
    let glb = GlbOptions {
        reuse: !no_reuse,
        quantize: quantize.then(|| quantization_budget(tolerance)),
        compress: match compress {
            Some(CompressArg::Meshopt) => Compression::Meshopt,
            None => Compression::None,
        },
        instancing,
        normals: match normals {
            NormalsArg::Smooth => Normals::Smooth,
            NormalsArg::Flat => Normals::Flat,
        },
    };
    let start = Instant::now();
    let to_stdout = output.as_os_str() == "-";
    if tiles.is_none()
        && !to_stdout
        && output
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("gltf"))
    {
        eprintln!(
            "error: {}: vesselcad writes binary glTF only; name the output .glb \
             (a .gltf file would be read as JSON glTF and fail)",
            output.display()
        );
        return ExitCode::from(2);
    }
    let d = match load(&design) {
        Ok(d) => d,
        Err(e) => return fail(&e),
    };
    let meshing = |tolerance: f64, glb: &GlbOptions| {
        TessellationOptions::chord(glb.meshing_tolerance(tolerance))
            .with_max_stretch(max_stretch)
            .with_max_vertices(max_vertices as usize)
    };
    if let (Some(dir), false) = (&tiles, lod.is_empty()) {
        return write_lod_tiles(&d, &design, &lod, dir, |t| {
            let glb = GlbOptions {
                quantize: quantize.then(|| quantization_budget(t)),
                ..glb
            };
            (glb, meshing(t, &glb), granularity.into())
        });
    }
    let mut model = match build_checked(&d, &design, meshing(tolerance, &glb)) {
        Ok(m) => m,
        Err(code) => return code,
    };
    let mut scene = match Granularity::from(granularity) {
        Granularity::Patch => model.scene(),
        g => merge_scene(&model.scene(), g),
    };
    if fab {
        return write_fab(&mut model, &mut scene, &glb, (tolerance, &output), start);
    }
    let triangles = triangle_count(&scene);
    if let Some(dir) = tiles {
        return match write_tiles(&scene, &glb, tolerance, &dir) {
            Ok(files) => {
                outln!(
                    "{}: {} vessel tile(s), {} triangles at {} mm, {:.0} ms",
                    dir.join(vesselcad::export::TILESET).display(),
                    files.len() - 1,
                    triangles,
                    tolerance,
                    start.elapsed().as_secs_f64() * 1e3
                );
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(2)
            }
        };
    }
    let written = if to_stdout {
        let stdout = std::io::stdout().lock();
        let mut out = std::io::BufWriter::new(stdout);
        stream_glb_with(&scene, &glb, &mut out, Path::new("<stdout>")).and_then(|n| {
            out.flush().map_err(|source| ExportError::Io {
                path: "<stdout>".into(),
                source,
            })?;
            Ok(n)
        })
    } else {
        stream_glb_with_to(&scene, &glb, &output)
    };
    let bytes = match written {
        Ok(bytes) => bytes,
        // The reader of standard output went away: it had what it wanted.
        Err(e) if to_stdout && is_broken_pipe(&e) => return ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    // On standard error when the GLB itself goes to standard output.
    let summary = format!(
        "{}: {} vessel(s), {} triangles at {} mm, {} bytes, {:.0} ms",
        if to_stdout {
            "<stdout>".into()
        } else {
            output.display().to_string()
        },
        scene.vessels.len(),
        triangles,
        tolerance,
        bytes,
        start.elapsed().as_secs_f64() * 1e3
    );
    if to_stdout {
        eprintln!("{summary}");
    } else {
        outln!("{summary}");
    }
    ExitCode::SUCCESS
}

/// Builds `d` (read from `path`) with a progress bar, printing what cannot be
/// built or what breaks a rule.
///
/// # Errors
///
/// The exit code to return: 2 when the design or its geometry cannot be built,
/// 1 when the model reports errors.
fn build_checked(d: &Design, path: &Path, options: TessellationOptions) -> Result<Model, ExitCode> {
    let model = match build_with_progress(d, options) {
        Ok(m) => m,
        Err(ModelError::Design(e)) => return Err(fail(&e)),
        Err(ModelError::Geometry(failures)) => {
            // Not a broken rule: what could not be built, by design path.
            eprintln!(
                "error: {}: the geometry cannot be built ({} failure(s)):",
                path.display(),
                failures.len()
            );
            for f in &failures {
                eprintln!("error: {f}");
            }
            return Err(ExitCode::from(2));
        }
        Err(e) => {
            eprintln!("error: {}: {}", path.display(), model_error(&e));
            return Err(ExitCode::from(2));
        }
    };
    if !model.errors().0.is_empty() {
        for failure in &model.errors().0 {
            eprintln!("error: {failure}");
        }
        return Err(ExitCode::from(1));
    }
    Ok(model)
}

/// `build --tiles DIR --lod t0,t1,…`: the design built at each tolerance (coarse
/// to fine), each level's vessels written and the model dropped before the
/// next, then the tileset. `level(t)` gives the GLB options, the meshing
/// options and the granularity of the level at tolerance `t`.
fn write_lod_tiles(
    d: &Design,
    path: &Path,
    tolerances: &[f64],
    dir: &Path,
    level: impl Fn(f64) -> (GlbOptions, TessellationOptions, Granularity),
) -> ExitCode {
    let start = Instant::now();
    let mut writer = match TilesWriter::new(dir, tolerances) {
        Ok(w) => w,
        Err(e) => {
            eprintln!("error: --lod: {e}");
            return ExitCode::from(2);
        }
    };
    let mut triangles = Vec::new();
    while let Some(t) = writer.next_tolerance() {
        let (glb, meshing, granularity) = level(t);
        let model = match build_checked(d, path, meshing) {
            Ok(m) => m,
            Err(code) => return code,
        };
        let scene = match granularity {
            Granularity::Patch => model.scene(),
            g => merge_scene(&model.scene(), g),
        };
        drop(model);
        triangles.push(format!("{} at {t} mm", triangle_count(&scene)));
        if let Err(e) = writer.add_level(&scene, &glb) {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    }
    match writer.finish() {
        Ok(files) => {
            outln!(
                "{}: {} level(s), {} file(s), triangles {}, {:.0} ms",
                dir.join(vesselcad::export::TILESET).display(),
                tolerances.len(),
                files.len() - 1,
                triangles.join(", "),
                start.elapsed().as_secs_f64() * 1e3
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// The triangles of every patch of `scene`.
fn triangle_count(scene: &Scene) -> usize {
    scene
        .vessels
        .iter()
        .flat_map(|v| &v.nodes)
        .flat_map(|n| &n.patches)
        .map(|p| p.mesh.triangle_count())
        .sum()
}

/// `build --fab`: the process plans kept by the model, their levels on the
/// scene's nodes and their seams as lines, written to `output` (or `-`).
fn write_fab(
    model: &mut Model,
    scene: &mut Scene,
    glb: &GlbOptions,
    (tolerance, output): (f64, &Path),
    start: Instant,
) -> ExitCode {
    model.set_process_planning(Some(Arc::new(ShopRules::builtin())));
    model.update();
    let mut plans = Vec::new();
    for vessel in &scene.vessels {
        match (model.fab_plan(&vessel.tag), model.process_plan(&vessel.tag)) {
            (Some(Ok(f)), Some(Ok(p))) => plans.push((f, p)),
            (Some(Err(e)), _) | (_, Some(Err(e))) => {
                eprintln!("warning: {}: no fabrication data: {e}", vessel.tag);
            }
            _ => {}
        }
    }
    let process: Vec<&ProcessPlan> = plans.iter().map(|(_, p)| &**p).collect();
    annotate_scene(scene, &process);
    let seams: Vec<_> = plans
        .iter()
        .map(|(f, p)| (f.tag.clone(), seam_lines(f, p, tolerance)))
        .collect();
    let bytes = match write_glb_with(scene, glb).map(|b| add_seams(&b, &seams)) {
        Ok(Ok(b)) => b,
        Ok(Err(e)) => {
            eprintln!("error: {}: {e}", output.display());
            return ExitCode::from(2);
        }
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let to_stdout = output.as_os_str() == "-";
    let written = if to_stdout {
        std::io::stdout().lock().write_all(&bytes)
    } else {
        std::fs::write(output, &bytes)
    };
    match written {
        Ok(()) => {}
        Err(e) if to_stdout && e.kind() == std::io::ErrorKind::BrokenPipe => {
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            eprintln!("error: {}: {e}", output.display());
            return ExitCode::from(2);
        }
    }
    let summary = format!(
        "{}: {} vessel(s) with fabrication data, {} seam(s), {} bytes, {:.0} ms",
        if to_stdout {
            "<stdout>".into()
        } else {
            output.display().to_string()
        },
        plans.len(),
        seams.iter().map(|(_, s)| s.len()).sum::<usize>(),
        bytes.len(),
        start.elapsed().as_secs_f64() * 1e3
    );
    if to_stdout {
        eprintln!("{summary}");
    } else {
        outln!("{summary}");
    }
    ExitCode::SUCCESS
}

/// Builds `design` with a progress bar on a terminal.
///
/// # Errors
///
/// As [`build_plant`].
pub fn build_with_progress(
    design: &Design,
    options: TessellationOptions,
) -> Result<Model, ModelError> {
    let progress = bar(design.vessels.len(), "building");
    let model = build_plant(design, options, &mut |done, _| {
        progress.set_position(done as u64)
    });
    progress.finish_and_clear();
    model
}
