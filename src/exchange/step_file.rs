//! The STEP file around the vessels' blocks (the blocks: `exchange::step`): the header
//! section and shared header block (contexts, units, the uncertainty), each
//! vessel's block moved to its place by [`rebase`], and the plant assembly
//! placing every vessel with its frame. Called by the exchange front
//! (`exchange::blocks`) once the blocks exist.

use std::fmt::Write as _;

use glam::DAffine3;

use super::step::{
    APPLICATION_CONTEXT, CONTEXT_2D, CONTEXT_3D, DEFINITION_CONTEXT, IDENTITY, LOCAL_BASE,
    PRODUCT_CONTEXT, StepBlock, VESSEL_DEFINITION, VESSEL_REPRESENTATION, Writer, real, rebase,
    string,
};

/// The header section and the header block of shared entities, the
/// geometric context's uncertainty `uncertainty` mm.
fn header(out: &mut String, name: &str, uncertainty: f64) {
    out.push_str(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('vesselcad exact model'),'2;1');\nFILE_NAME(",
    );
    string(out, name);
    out.push_str(",'1970-01-01T00:00:00',(''),(''),'vesselcad','vesselcad','');\n");
    out.push_str("FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n");
    let _ = write!(
        out,
        "#{APPLICATION_CONTEXT}=APPLICATION_CONTEXT('core data for automotive mechanical design processes');\n\
         #2=APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#1);\n\
         #{PRODUCT_CONTEXT}=PRODUCT_CONTEXT('',#1,'mechanical');\n\
         #{DEFINITION_CONTEXT}=PRODUCT_DEFINITION_CONTEXT('part definition',#1,'design');\n\
         #5=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));\n\
         #6=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));\n\
         #7=(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT());\n\
         #8=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE("
    );
    real(out, uncertainty);
    let _ = write!(
        out,
        "),#5,'distance_accuracy_value','confusion accuracy');\n\
         #{CONTEXT_3D}=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#8))GLOBAL_UNIT_ASSIGNED_CONTEXT((#5,#6,#7))REPRESENTATION_CONTEXT('3D','millimetres'));\n\
         #{CONTEXT_2D}=(GEOMETRIC_REPRESENTATION_CONTEXT(2)PARAMETRIC_REPRESENTATION_CONTEXT()REPRESENTATION_CONTEXT('2D SPACE',''));\n\
         #11=CARTESIAN_POINT('',(0.0,0.0,0.0));\n\
         #12=DIRECTION('',(0.0,0.0,1.0));\n\
         #13=DIRECTION('',(1.0,0.0,0.0));\n\
         #{IDENTITY}=AXIS2_PLACEMENT_3D('',#11,#12,#13);\n"
    );
}

/// A vessel's block with its tag and its place in the plant.
#[derive(Clone, Debug)]
pub struct PlacedBlock {
    /// The vessel's tag.
    pub tag: String,
    /// Vessel frame → plant frame.
    pub frame: DAffine3,
    /// Its entities.
    pub block: std::sync::Arc<StepBlock>,
}

/// Writes the whole file: header, the vessels' blocks, the plant assembly.
///
/// The file's uncertainty (`distance_accuracy_value`) is the largest of the
/// vessels' exchange tolerances (1e-3 mm without vessels): an opening loop's
/// 3D curve and its pcurves' images are fitted separately, each within half
/// of it, so they agree to it and not closer. A receiver that finds a pcurve
/// further from its 3D curve than about twice the uncertainty may replace it
/// by a projection of the 3D curve (OpenCASCADE's STEP reader does), which
/// moves the face's boundary across the curve: along the long edge of a
/// reinforcing pad's sliver beside a seam, with 1e-6 mm stated, by 5.8e-6 of
/// the sliver's area.
pub fn write_step(name: &str, vessels: &[PlacedBlock]) -> String {
    let total: usize = vessels.iter().map(|v| v.block.text.len()).sum();
    let mut out = String::with_capacity(total + 4096 + 1024 * vessels.len());
    let uncertainty = vessels
        .iter()
        .map(|v| v.block.tolerance)
        .reduce(f64::max)
        .unwrap_or(super::ExchangeOptions::DEFAULT.tolerance);
    header(&mut out, name, uncertainty);
    let mut offset = 0;
    let mut placed = Vec::with_capacity(vessels.len());
    for vessel in vessels {
        rebase(&mut out, &vessel.block.text, offset);
        placed.push((vessel, offset));
        offset += vessel.block.next - LOCAL_BASE;
    }
    let mut w = Writer {
        out,
        next: LOCAL_BASE + offset,
    };
    let (product, formation, definition, shape, representation) =
        (w.next, w.next + 1, w.next + 2, w.next + 3, w.next + 4);
    w.next += 5;
    let _ = writeln!(
        w.out,
        "#{product}=PRODUCT('plant','plant','plant',(#{PRODUCT_CONTEXT}));\n\
         #{formation}=PRODUCT_DEFINITION_FORMATION('','',#{product});\n\
         #{definition}=PRODUCT_DEFINITION('design','',#{formation},#{DEFINITION_CONTEXT});\n\
         #{shape}=PRODUCT_DEFINITION_SHAPE('','',#{definition});\n\
         #{}=SHAPE_DEFINITION_REPRESENTATION(#{shape},#{representation});",
        w.next
    );
    w.next += 1;
    let mut items = vec![IDENTITY];
    for (brep, offset) in placed {
        let frame: DAffine3 = brep.frame;
        let place = w.placement(
            &brep.tag,
            frame.translation,
            frame.matrix3.z_axis.normalize(),
            frame.matrix3.x_axis.normalize(),
        );
        items.push(place);
        let transformation = w.begin();
        let _ = write!(
            w.out,
            "ITEM_DEFINED_TRANSFORMATION('','',#{IDENTITY},#{place})"
        );
        w.end();
        let relationship = w.begin();
        let _ = write!(
            w.out,
            "(REPRESENTATION_RELATIONSHIP('','',#{},#{representation})REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#{transformation})SHAPE_REPRESENTATION_RELATIONSHIP())",
            VESSEL_REPRESENTATION + offset
        );
        w.end();
        let usage = w.begin();
        w.out.push_str("NEXT_ASSEMBLY_USAGE_OCCURRENCE(");
        string(&mut w.out, &brep.tag);
        w.out.push(',');
        string(&mut w.out, &brep.tag);
        let _ = write!(
            w.out,
            ",'',#{definition},#{},$)",
            VESSEL_DEFINITION + offset
        );
        w.end();
        let placement_shape = w.begin();
        let _ = write!(
            w.out,
            "PRODUCT_DEFINITION_SHAPE('Placement','Placement of an item',#{usage})"
        );
        w.end();
        w.begin();
        let _ = write!(
            w.out,
            "CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#{relationship},#{placement_shape})"
        );
        w.end();
    }
    let _ = write!(w.out, "#{representation}=SHAPE_REPRESENTATION('plant',");
    w.refs(&items);
    let _ = write!(w.out, ",#{CONTEXT_3D})");
    w.end();
    w.out.push_str("ENDSEC;\nEND-ISO-10303-21;\n");
    w.out
}
