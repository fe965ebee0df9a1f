//! `poinav export glb|fbx`: the building's element meshes (openings cut) as binary glTF or
//! binary FBX 7.4, grouped by storey, with GlobalId, class, storey and POI data per element.

use std::path::PathBuf;
use std::process::ExitCode;

use poinav_export::SceneInput;
use poinav_ifc::{spatial, units, Model};
use poinav_poi::classify;

use crate::warnings::Warning;

/// Export formats.
#[derive(Debug, clap::Subcommand)]
pub enum Export {
    /// glTF 2.0 binary: one node per element under storey nodes, Y up, `extras` with GlobalId,
    /// IFC class, storey, POI category, roles and accessibility status.
    Glb(MeshArgs),
    /// Binary FBX 7.4 (what Unity imports): the same hierarchy, names carrying the GlobalId.
    Fbx(MeshArgs),
    /// A Nav2 bundle per storey: map, keepout and speed masks, costmap filter info, route graph.
    Nav2(crate::navigate::Nav2Args),
}

/// Arguments of the 3D exports.
#[derive(Debug, clap::Args)]
pub struct MeshArgs {
    /// The IFC file (never modified).
    file: PathBuf,
    /// Where to write.
    #[arg(short, long)]
    output: PathBuf,
    /// Robot profile for the accessibility status in the metadata (default: the paper's robot).
    #[arg(long)]
    profile: Option<PathBuf>,
    /// Rule file extending the default POI rules.
    #[arg(long)]
    rules: Option<PathBuf>,
    /// Leave POI data out of the metadata.
    #[arg(long)]
    no_poi: bool,
    /// GLB only: one mesh per element, `f32` positions and normals, no extension (for readers
    /// without `KHR_mesh_quantization`); the default shares copies' meshes and quantises.
    #[arg(long)]
    plain: bool,
}

/// Runs `poinav export ...`.
pub fn run(export: &Export) -> anyhow::Result<ExitCode> {
    let (args, format) = match export {
        Export::Glb(a) => (a, "glb"),
        Export::Fbx(a) => (a, "fbx"),
        Export::Nav2(a) => return crate::navigate::nav2(a),
    };
    crate::progress::stage("reading");
    let model = Model::open(&args.file)?;
    crate::progress::stage("meshing");
    let meshes = poinav_geom::mesh_model_with_progress(
        &model,
        poinav_geom::PRODUCT_TIME_LIMIT,
        &crate::progress::tick,
    );
    crate::progress::end();
    let unit = units::length_unit(&model);
    let structure = spatial::spatial_structure(&model, &unit);
    let problems = problems(&model, &meshes);
    crate::warnings::print(&problems);
    crate::ensure_geometry(
        &args.file,
        meshes.elements.len() + meshes.spaces.len(),
        meshes.failures.len(),
    )?;
    crate::progress::stage("classifying");
    let classification = if args.no_poi {
        None
    } else {
        let rules = crate::rules(args.rules.as_deref())?;
        let profile = crate::profile(args.profile.as_deref())?;
        Some(classify(&model, &rules, &profile))
    };
    let scene = SceneInput {
        storeys: &structure.storeys,
        elements: &meshes.elements,
        poi: classification.as_ref(),
    };
    crate::progress::stage("writing");
    match format {
        "glb" => {
            let options = if args.plain {
                poinav_export::glb::GlbOptions::PLAIN
            } else {
                poinav_export::glb::GlbOptions::COMPACT
            };
            poinav_export::glb::write_glb_with(&args.output, &scene, options)
        }
        _ => poinav_export::fbx::write_fbx(&args.output, &scene),
    }?; // The error names the file and the cause.
    crate::progress::end();
    let triangles: usize = meshes.elements.iter().map(|e| e.mesh.triangles.len()).sum();
    outln!(
        "wrote {}: {} elements ({} triangles) on {} storeys; {} elements without geometry ({} failed, {} without a representation)",
        args.output.display(),
        meshes.elements.len(),
        triangles,
        structure.storeys.len(),
        meshes.failures.len() + meshes.without_geometry.len(),
        meshes.failures.len(),
        meshes.without_geometry.len(),
    );
    Ok(ExitCode::SUCCESS)
}

/// The elements left out of the export, as warnings: those whose mesh failed and those
/// without a representation; and those exported without an opening or boolean operand that
/// could not be made.
fn problems(model: &Model, meshes: &poinav_geom::ModelMeshes) -> Vec<Warning> {
    let class = |id| model.entity(id).map(|e| e.type_name().to_string());
    let failed = meshes
        .failures
        .iter()
        .map(|(id, e)| Warning::of(id, class(*id), e.to_string()));
    let absent = meshes.without_geometry.iter().map(|&id| {
        let name = model
            .entity(id)
            .and_then(|e| e.name())
            .map(|n| format!(" '{n}'"))
            .unwrap_or_default();
        let class = class(id);
        Warning::of(
            id,
            class.clone(),
            format!(
                "{}{name} has no Representation: not in the export",
                class.unwrap_or_default()
            ),
        )
        .grouped_by("has no Representation: not in the export")
    });
    // Meshed, but without an opening or boolean operand that could not be made.
    let uncut = crate::warnings::uncut(model, meshes);
    failed.chain(absent).chain(uncut).collect()
}
