//! A thin layer over `poinav_ifc::Editor` for writing geometry: points, directions, placements,
//! extruded rectangles, styled items, all with deterministic GlobalIds.

use poinav_ifc::{Arg, EditError, Editor, EntityId, GlobalId};

/// Adds instances with short calls; GlobalIds are derived from `namespace` and a key.
pub(crate) struct StepBuilder<'e, 'm> {
    pub(crate) ed: &'e mut Editor<'m>,
    namespace: String,
}

/// A real rounded to 1e-9, so sums like 0.2 + 0.1 are written as 0.3.
pub(crate) fn real(v: f64) -> Arg {
    Arg::Real((v * 1e9).round() / 1e9)
}

pub(crate) fn text(s: &str) -> Arg {
    Arg::Text(s.to_string())
}

pub(crate) fn refs(ids: &[EntityId]) -> Arg {
    Arg::List(ids.iter().map(|&i| Arg::Ref(i)).collect())
}

impl<'e, 'm> StepBuilder<'e, 'm> {
    pub(crate) fn new(ed: &'e mut Editor<'m>, namespace: &str) -> Self {
        StepBuilder {
            ed,
            namespace: namespace.to_string(),
        }
    }

    pub(crate) fn guid(&self, key: &str) -> Arg {
        Arg::Text(GlobalId::from_name(&self.namespace, key).to_string())
    }

    pub(crate) fn add(&mut self, entity: &str, args: Vec<Arg>) -> Result<EntityId, EditError> {
        self.ed.add(entity, args)
    }

    pub(crate) fn point3(&mut self, x: f64, y: f64, z: f64) -> Result<EntityId, EditError> {
        self.add(
            "IfcCartesianPoint",
            vec![Arg::List(vec![real(x), real(y), real(z)])],
        )
    }

    pub(crate) fn point2(&mut self, x: f64, y: f64) -> Result<EntityId, EditError> {
        self.add("IfcCartesianPoint", vec![Arg::List(vec![real(x), real(y)])])
    }

    pub(crate) fn direction(&mut self, d: &[f64]) -> Result<EntityId, EditError> {
        self.add(
            "IfcDirection",
            vec![Arg::List(d.iter().map(|&v| real(v)).collect())],
        )
    }

    /// An IfcAxis2Placement3D at (x, y, z) whose local X axis points along `x_axis` (horizontal).
    pub(crate) fn axis3(
        &mut self,
        x: f64,
        y: f64,
        z: f64,
        x_axis: Option<[f64; 2]>,
    ) -> Result<EntityId, EditError> {
        let origin = self.point3(x, y, z)?;
        let (axis, refdir) = match x_axis {
            Some([dx, dy]) => (
                Arg::Ref(self.direction(&[0.0, 0.0, 1.0])?),
                Arg::Ref(self.direction(&[dx, dy, 0.0])?),
            ),
            None => (Arg::Null, Arg::Null),
        };
        self.add("IfcAxis2Placement3D", vec![Arg::Ref(origin), axis, refdir])
    }

    pub(crate) fn local_placement(
        &mut self,
        relative_to: Option<EntityId>,
        axis: EntityId,
    ) -> Result<EntityId, EditError> {
        self.add(
            "IfcLocalPlacement",
            vec![relative_to.map_or(Arg::Null, Arg::Ref), Arg::Ref(axis)],
        )
    }

    /// A body representation: a `dx` x `dy` rectangle centred on (cx, cy), extruded `height` up from `z0`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn box_body(
        &mut self,
        context: EntityId,
        cx: f64,
        cy: f64,
        z0: f64,
        dx: f64,
        dy: f64,
        height: f64,
        style: Option<EntityId>,
    ) -> Result<EntityId, EditError> {
        let centre = self.point2(cx, cy)?;
        let position2 = self.add("IfcAxis2Placement2D", vec![Arg::Ref(centre), Arg::Null])?;
        let profile = self.add(
            "IfcRectangleProfileDef",
            vec![
                Arg::Enum("AREA".into()),
                Arg::Null,
                Arg::Ref(position2),
                real(dx),
                real(dy),
            ],
        )?;
        let position3 = self.axis3(0.0, 0.0, z0, None)?;
        let up = self.direction(&[0.0, 0.0, 1.0])?;
        let solid = self.add(
            "IfcExtrudedAreaSolid",
            vec![
                Arg::Ref(profile),
                Arg::Ref(position3),
                Arg::Ref(up),
                real(height),
            ],
        )?;
        if let Some(style) = style {
            self.add(
                "IfcStyledItem",
                vec![Arg::Ref(solid), refs(&[style]), Arg::Null],
            )?;
        }
        let rep = self.add(
            "IfcShapeRepresentation",
            vec![
                Arg::Ref(context),
                text("Body"),
                text("SweptSolid"),
                refs(&[solid]),
            ],
        )?;
        self.add(
            "IfcProductDefinitionShape",
            vec![Arg::Null, Arg::Null, refs(&[rep])],
        )
    }

    /// An IfcSurfaceStyle with one shading colour.
    pub(crate) fn surface_style(
        &mut self,
        name: &str,
        rgb: [f64; 3],
    ) -> Result<EntityId, EditError> {
        let colour = self.add(
            "IfcColourRgb",
            vec![Arg::Null, real(rgb[0]), real(rgb[1]), real(rgb[2])],
        )?;
        let shading = self.add("IfcSurfaceStyleShading", vec![Arg::Ref(colour), Arg::Null])?;
        self.add(
            "IfcSurfaceStyle",
            vec![text(name), Arg::Enum("BOTH".into()), refs(&[shading])],
        )
    }

    pub(crate) fn rel(
        &mut self,
        entity: &str,
        key: &str,
        mut rest: Vec<Arg>,
    ) -> Result<EntityId, EditError> {
        let mut args = vec![self.guid(key), Arg::Null, Arg::Null, Arg::Null];
        args.append(&mut rest);
        self.add(entity, args)
    }
}
