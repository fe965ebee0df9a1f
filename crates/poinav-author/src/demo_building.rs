//! The paper's test building (SPEC.md §6) as IFC4X3_ADD2: one storey, a central corridor with
//! rooms on both sides, exterior and corridor walls, one door per room in a real opening, a
//! floor slab, and a space for every room and the corridor.

use poinav_ifc::{Arg, Editor, EntityId, Model};

use crate::error::AuthorError;
use crate::step_builder::{real, refs, text, StepBuilder};

/// The building's dimensions (metres). Rooms are numbered west to east, first along the south
/// side of the corridor (Room 1, Room 2, ...), then along the north side.
#[derive(Debug, Clone, PartialEq)]
pub struct DemoBuilding {
    /// Rooms on each side of the corridor.
    pub rooms_per_side: usize,
    /// Inside width of a room along the corridor.
    pub room_width_m: f64,
    /// Inside depth of a room away from the corridor.
    pub room_depth_m: f64,
    /// Inside width of the corridor.
    pub corridor_width_m: f64,
    /// Thickness of every wall.
    pub wall_thickness_m: f64,
    /// Height of walls and spaces.
    pub wall_height_m: f64,
    /// Width of the door into Room 2 (0.80 m in the paper's first design).
    pub room2_door_width_m: f64,
    /// Width of every other door.
    pub door_width_m: f64,
    /// Height of every door.
    pub door_height_m: f64,
}

impl Default for DemoBuilding {
    fn default() -> Self {
        DemoBuilding {
            rooms_per_side: 3,
            room_width_m: 4.0,
            room_depth_m: 4.0,
            corridor_width_m: 2.4,
            wall_thickness_m: 0.2,
            wall_height_m: 3.0,
            room2_door_width_m: 0.80,
            door_width_m: 1.0,
            door_height_m: 2.1,
        }
    }
}

/// A door in a corridor wall.
#[derive(Debug, Clone, PartialEq)]
pub struct DoorLayout {
    /// `Door Room 2`.
    pub name: String,
    /// Centre of the opening, world XY.
    pub center: [f64; 2],
    /// Opening width.
    pub width_m: f64,
    /// +1 when the room is north of the corridor, -1 when south.
    pub side: f64,
}

/// A room and its door.
#[derive(Debug, Clone, PartialEq)]
pub struct RoomLayout {
    /// `Room 2`.
    pub name: String,
    /// Inside rectangle, world XY: min and max corners.
    pub min: [f64; 2],
    /// Max corner.
    pub max: [f64; 2],
    /// Its door.
    pub door: DoorLayout,
}

/// Where everything is, world metres (the storey is at elevation 0).
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// Rooms in number order.
    pub rooms: Vec<RoomLayout>,
    /// Corridor inside rectangle: min corner.
    pub corridor_min: [f64; 2],
    /// Corridor max corner.
    pub corridor_max: [f64; 2],
}

impl DemoBuilding {
    fn check(&self) -> Result<(), AuthorError> {
        let sizes = [
            ("room width", self.room_width_m),
            ("room depth", self.room_depth_m),
            ("corridor width", self.corridor_width_m),
            ("wall thickness", self.wall_thickness_m),
            ("wall height", self.wall_height_m),
            ("Room 2 door width", self.room2_door_width_m),
            ("door width", self.door_width_m),
            ("door height", self.door_height_m),
        ];
        for (what, value) in sizes {
            if !(value.is_finite() && value > 0.0) {
                return Err(AuthorError::BadSize { what, value });
            }
        }
        let widest = self.room2_door_width_m.max(self.door_width_m);
        if widest > self.room_width_m - 0.2
            || self.door_height_m >= self.wall_height_m
            || self.rooms_per_side == 0
        {
            return Err(AuthorError::BadSize {
                what: "door (must fit its wall)",
                value: widest,
            });
        }
        Ok(())
    }

    /// Inside length of the building along the corridor.
    pub fn length_m(&self) -> f64 {
        let n = self.rooms_per_side as f64;
        n * self.room_width_m + (n - 1.0) * self.wall_thickness_m
    }

    /// Inside extent across the corridor (south rooms, corridor, north rooms, two corridor walls).
    pub fn depth_m(&self) -> f64 {
        2.0 * self.room_depth_m + self.corridor_width_m + 2.0 * self.wall_thickness_m
    }

    /// The rooms, doors and corridor.
    pub fn layout(&self) -> Layout {
        let t = self.wall_thickness_m;
        let corridor_y0 = self.room_depth_m + t;
        let corridor_y1 = corridor_y0 + self.corridor_width_m;
        let mut rooms = Vec::new();
        for (side, y0, y1, wall_y) in [
            (-1.0, 0.0, self.room_depth_m, self.room_depth_m + t / 2.0),
            (
                1.0,
                corridor_y1 + t,
                corridor_y1 + t + self.room_depth_m,
                corridor_y1 + t / 2.0,
            ),
        ] {
            for i in 0..self.rooms_per_side {
                let number = rooms.len() + 1;
                let x0 = i as f64 * (self.room_width_m + t);
                let width = if number == 2 {
                    self.room2_door_width_m
                } else {
                    self.door_width_m
                };
                rooms.push(RoomLayout {
                    name: format!("Room {number}"),
                    min: [x0, y0],
                    max: [x0 + self.room_width_m, y1],
                    door: DoorLayout {
                        name: format!("Door Room {number}"),
                        center: [x0 + self.room_width_m / 2.0, wall_y],
                        width_m: width,
                        side,
                    },
                });
            }
        }
        Layout {
            rooms,
            corridor_min: [0.0, corridor_y0],
            corridor_max: [self.length_m(), corridor_y1],
        }
    }
}

const TEMPLATE: &str = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('ViewDefinition [ReferenceView]'),'2;1');\n\
FILE_NAME('poinav-demo-building.ifc','1970-01-01T00:00:00',('poinav'),('poinav'),'poinav','poinav','');\n\
FILE_SCHEMA(('IFC4X3_ADD2'));\nENDSEC;\nDATA;\nENDSEC;\nEND-ISO-10303-21;\n";

struct Ctx {
    body: EntityId,
    storey_placement: EntityId,
    wall_style: EntityId,
    door_style: EntityId,
    slab_style: EntityId,
}

/// Writes the building; `timestamp` goes into the header (ISO 8601).
pub fn demo_building(spec: &DemoBuilding, timestamp: &str) -> Result<Vec<u8>, AuthorError> {
    spec.check()?;
    let model = Model::from_bytes("poinav-demo-building.ifc", TEMPLATE.as_bytes().to_vec())?;
    let mut ed = Editor::new(&model);
    ed.set_timestamp(timestamp);
    let mut b = StepBuilder::new(&mut ed, "poinav-demo-building");
    write_building(&mut b, spec)?;
    Ok(ed.to_bytes())
}

fn write_building(b: &mut StepBuilder<'_, '_>, spec: &DemoBuilding) -> Result<(), AuthorError> {
    // Units, contexts, project and spatial structure.
    let units: Vec<EntityId> = [
        ("LENGTHUNIT", "METRE"),
        ("AREAUNIT", "SQUARE_METRE"),
        ("VOLUMEUNIT", "CUBIC_METRE"),
        ("PLANEANGLEUNIT", "RADIAN"),
    ]
    .iter()
    .map(|(kind, name)| {
        b.add(
            "IfcSIUnit",
            vec![
                Arg::Derived,
                Arg::Enum((*kind).into()),
                Arg::Null,
                Arg::Enum((*name).into()),
            ],
        )
    })
    .collect::<Result<_, _>>()?;
    let assignment = b.add("IfcUnitAssignment", vec![refs(&units)])?;
    let world = b.axis3(0.0, 0.0, 0.0, None)?;
    let context = b.add(
        "IfcGeometricRepresentationContext",
        vec![
            Arg::Null,
            text("Model"),
            Arg::Integer(3),
            real(1e-5),
            Arg::Ref(world),
            Arg::Null,
        ],
    )?;
    let body = b.add(
        "IfcGeometricRepresentationSubContext",
        vec![
            text("Body"),
            text("Model"),
            Arg::Derived,
            Arg::Derived,
            Arg::Derived,
            Arg::Derived,
            Arg::Ref(context),
            Arg::Null,
            Arg::Enum("MODEL_VIEW".into()),
            Arg::Null,
        ],
    )?;
    let project = b.add(
        "IfcProject",
        vec![
            b.guid("project"),
            Arg::Null,
            text("poinav test building"),
            text("The test building of the POI paper: a corridor with rooms on both sides"),
            Arg::Null,
            Arg::Null,
            Arg::Null,
            refs(&[context]),
            Arg::Ref(assignment),
        ],
    )?;
    let site_axis = b.axis3(0.0, 0.0, 0.0, None)?;
    let site_placement = b.local_placement(None, site_axis)?;
    let site = b.add(
        "IfcSite",
        vec![
            b.guid("site"),
            Arg::Null,
            text("Site"),
            Arg::Null,
            Arg::Null,
            Arg::Ref(site_placement),
            Arg::Null,
            Arg::Null,
            Arg::Enum("ELEMENT".into()),
            Arg::Null,
            Arg::Null,
            Arg::Null,
            Arg::Null,
            Arg::Null,
        ],
    )?;
    let building_axis = b.axis3(0.0, 0.0, 0.0, None)?;
    let building_placement = b.local_placement(Some(site_placement), building_axis)?;
    let building = b.add(
        "IfcBuilding",
        vec![
            b.guid("building"),
            Arg::Null,
            text("Test building"),
            Arg::Null,
            Arg::Null,
            Arg::Ref(building_placement),
            Arg::Null,
            Arg::Null,
            Arg::Enum("ELEMENT".into()),
            Arg::Null,
            Arg::Null,
            Arg::Null,
        ],
    )?;
    let storey_axis = b.axis3(0.0, 0.0, 0.0, None)?;
    let storey_placement = b.local_placement(Some(building_placement), storey_axis)?;
    let storey = b.add(
        "IfcBuildingStorey",
        vec![
            b.guid("storey"),
            Arg::Null,
            text("Ground floor"),
            Arg::Null,
            Arg::Null,
            Arg::Ref(storey_placement),
            Arg::Null,
            Arg::Null,
            Arg::Enum("ELEMENT".into()),
            real(0.0),
        ],
    )?;
    b.rel(
        "IfcRelAggregates",
        "agg/project",
        vec![Arg::Ref(project), refs(&[site])],
    )?;
    b.rel(
        "IfcRelAggregates",
        "agg/site",
        vec![Arg::Ref(site), refs(&[building])],
    )?;
    b.rel(
        "IfcRelAggregates",
        "agg/building",
        vec![Arg::Ref(building), refs(&[storey])],
    )?;
    let ctx = Ctx {
        body,
        storey_placement,
        wall_style: b.surface_style("Wall", [0.85, 0.85, 0.82])?,
        door_style: b.surface_style("Door", [0.55, 0.35, 0.2])?,
        slab_style: b.surface_style("Floor", [0.45, 0.45, 0.45])?,
    };

    let layout = spec.layout();
    let t = spec.wall_thickness_m;
    let (lx, ly) = (spec.length_m(), spec.depth_m());
    let mut contained = Vec::new();

    // Walls: (name, centre start, direction, length).
    let corridor_south_y = layout.corridor_min[1] - t / 2.0;
    let corridor_north_y = layout.corridor_max[1] + t / 2.0;
    let mut walls: Vec<(String, [f64; 2], [f64; 2], f64)> = vec![
        (
            "Exterior wall south".into(),
            [-t, -t / 2.0],
            [1.0, 0.0],
            lx + 2.0 * t,
        ),
        (
            "Exterior wall north".into(),
            [-t, ly + t / 2.0],
            [1.0, 0.0],
            lx + 2.0 * t,
        ),
        ("Exterior wall west".into(), [-t / 2.0, 0.0], [0.0, 1.0], ly),
        (
            "Exterior wall east".into(),
            [lx + t / 2.0, 0.0],
            [0.0, 1.0],
            ly,
        ),
        (
            "Corridor wall south".into(),
            [0.0, corridor_south_y],
            [1.0, 0.0],
            lx,
        ),
        (
            "Corridor wall north".into(),
            [0.0, corridor_north_y],
            [1.0, 0.0],
            lx,
        ),
    ];
    for i in 1..spec.rooms_per_side {
        let x = i as f64 * (spec.room_width_m + t) - t / 2.0;
        walls.push((
            format!("Partition wall south {i}"),
            [x, 0.0],
            [0.0, 1.0],
            spec.room_depth_m,
        ));
        walls.push((
            format!("Partition wall north {i}"),
            [x, layout.corridor_max[1] + t],
            [0.0, 1.0],
            spec.room_depth_m,
        ));
    }
    let mut wall_ids = Vec::new();
    for (name, start, dir, length) in &walls {
        let axis = b.axis3(start[0], start[1], 0.0, Some(*dir))?;
        let placement = b.local_placement(Some(ctx.storey_placement), axis)?;
        let shape = b.box_body(
            ctx.body,
            length / 2.0,
            0.0,
            0.0,
            *length,
            t,
            spec.wall_height_m,
            Some(ctx.wall_style),
        )?;
        let wall = b.add(
            "IfcWall",
            vec![
                b.guid(&format!("wall/{name}")),
                Arg::Null,
                text(name),
                Arg::Null,
                Arg::Null,
                Arg::Ref(placement),
                Arg::Ref(shape),
                Arg::Null,
                Arg::Enum(
                    if name.starts_with("Exterior") {
                        "SOLIDWALL"
                    } else {
                        "PARTITIONING"
                    }
                    .into(),
                ),
            ],
        )?;
        contained.push(wall);
        wall_ids.push((name.clone(), wall, placement, *start));
    }

    // Spaces.
    let mut space_ids = Vec::new();
    let mut spaces: Vec<(String, String, [f64; 2], [f64; 2])> = layout
        .rooms
        .iter()
        .map(|r| (r.name.clone(), r.name.clone(), r.min, r.max))
        .collect();
    spaces.push((
        "Corridor".into(),
        "Corridor".into(),
        layout.corridor_min,
        layout.corridor_max,
    ));
    for (name, long_name, min, max) in &spaces {
        let axis = b.axis3(min[0], min[1], 0.0, None)?;
        let placement = b.local_placement(Some(ctx.storey_placement), axis)?;
        let (w, d) = (max[0] - min[0], max[1] - min[1]);
        let shape = b.box_body(
            ctx.body,
            w / 2.0,
            d / 2.0,
            0.0,
            w,
            d,
            spec.wall_height_m,
            None,
        )?;
        let space = b.add(
            "IfcSpace",
            vec![
                b.guid(&format!("space/{name}")),
                Arg::Null,
                text(name),
                Arg::Null,
                Arg::Null,
                Arg::Ref(placement),
                Arg::Ref(shape),
                text(long_name),
                Arg::Enum("ELEMENT".into()),
                Arg::Enum("INTERNAL".into()),
                Arg::Null,
            ],
        )?;
        space_ids.push((name.clone(), space));
    }
    b.rel(
        "IfcRelAggregates",
        "agg/storey",
        vec![
            Arg::Ref(storey),
            refs(&space_ids.iter().map(|s| s.1).collect::<Vec<_>>()),
        ],
    )?;
    let corridor_space = space_ids.last().expect("corridor space").1;

    // Doors in openings of the corridor walls.
    for (room, (_, room_space)) in layout.rooms.iter().zip(&space_ids) {
        let wall_name = if room.door.side < 0.0 {
            "Corridor wall south"
        } else {
            "Corridor wall north"
        };
        let (_, wall, wall_placement, start) = wall_ids
            .iter()
            .find(|w| w.0 == wall_name)
            .expect("corridor wall")
            .clone();
        let along = room.door.center[0] - start[0];
        let key = &room.door.name;
        let opening_axis = b.axis3(along, 0.0, 0.0, None)?;
        let opening_placement = b.local_placement(Some(wall_placement), opening_axis)?;
        let opening_shape = b.box_body(
            ctx.body,
            0.0,
            0.0,
            0.0,
            room.door.width_m,
            t + 0.1,
            spec.door_height_m,
            None,
        )?;
        let opening = b.add(
            "IfcOpeningElement",
            vec![
                b.guid(&format!("opening/{key}")),
                Arg::Null,
                text(&format!("Opening {}", room.name)),
                Arg::Null,
                Arg::Null,
                Arg::Ref(opening_placement),
                Arg::Ref(opening_shape),
                Arg::Null,
                Arg::Enum("OPENING".into()),
            ],
        )?;
        b.rel(
            "IfcRelVoidsElement",
            &format!("voids/{key}"),
            vec![Arg::Ref(wall), Arg::Ref(opening)],
        )?;
        let door_axis = b.axis3(0.0, 0.0, 0.0, None)?;
        let door_placement = b.local_placement(Some(opening_placement), door_axis)?;
        let door_shape = b.box_body(
            ctx.body,
            0.0,
            0.0,
            0.0,
            room.door.width_m,
            0.05,
            spec.door_height_m,
            Some(ctx.door_style),
        )?;
        let door = b.add(
            "IfcDoor",
            vec![
                b.guid(&format!("door/{key}")),
                Arg::Null,
                text(key),
                Arg::Null,
                Arg::Null,
                Arg::Ref(door_placement),
                Arg::Ref(door_shape),
                Arg::Null,
                real(spec.door_height_m),
                real(room.door.width_m),
                Arg::Enum("DOOR".into()),
                Arg::Enum("SINGLE_SWING_LEFT".into()),
                Arg::Null,
            ],
        )?;
        b.rel(
            "IfcRelFillsElement",
            &format!("fills/{key}"),
            vec![Arg::Ref(opening), Arg::Ref(door)],
        )?;
        for (space, side) in [(*room_space, "room"), (corridor_space, "corridor")] {
            b.rel(
                "IfcRelSpaceBoundary",
                &format!("boundary/{key}/{side}"),
                vec![
                    Arg::Ref(space),
                    Arg::Ref(door),
                    Arg::Null,
                    Arg::Enum("PHYSICAL".into()),
                    Arg::Enum("INTERNAL".into()),
                ],
            )?;
        }
        contained.push(door);
    }

    // Floor slab under everything, top at elevation 0.
    let slab_axis = b.axis3(0.0, 0.0, 0.0, None)?;
    let slab_placement = b.local_placement(Some(ctx.storey_placement), slab_axis)?;
    let slab_shape = b.box_body(
        ctx.body,
        lx / 2.0,
        ly / 2.0,
        -0.2,
        lx + 2.0 * t,
        ly + 2.0 * t,
        0.2,
        Some(ctx.slab_style),
    )?;
    let slab = b.add(
        "IfcSlab",
        vec![
            b.guid("slab"),
            Arg::Null,
            text("Floor slab"),
            Arg::Null,
            Arg::Null,
            Arg::Ref(slab_placement),
            Arg::Ref(slab_shape),
            Arg::Null,
            Arg::Enum("FLOOR".into()),
        ],
    )?;
    contained.push(slab);
    b.rel(
        "IfcRelContainedInSpatialStructure",
        "contained/storey",
        vec![refs(&contained), Arg::Ref(storey)],
    )?;
    Ok(())
}
