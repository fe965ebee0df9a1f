//! Binary FBX 7.4 (`.fbx`, what Unity's importer reads) of a building's element meshes, with
//! the same storey -> element hierarchy, frame and pivots as the GLB ([`crate::scene`]).
//!
//! The file is written node record by node record (FBX is a tree of named records, each with
//! a tuple of typed properties and nested records; see [`Node`] and [`Prop`]):
//!
//! - Header: `Kaydara FBX Binary  \0`, `0x1A 0x00`, version `7400` (u32). Records use u32
//!   end offsets (absolute file positions), so a file is limited to 4 GiB.
//! - `FBXHeaderExtension`, `FileId`, `CreationTime`, `Creator`: the file id, creation time and
//!   footer id are the fixed values other open exporters use, which the FBX SDK accepts (it
//!   checks them against each other); the output is therefore the same bytes for the same
//!   scene.
//! - `GlobalSettings`: Y up, Z front, X right (right-handed), `UnitScaleFactor` 100 (one unit
//!   is one metre; FBX counts in centimetres).
//! - `Documents`, `References`, `Definitions` (object counts per type).
//! - `Objects`: a `Model` (`Null`, with its `NodeAttribute`) per storey group; a `Model`
//!   (`Mesh`) per element with triangles and its `Geometry` (`Vertices`, `PolygonVertexIndex`
//!   with the last index of each triangle stored as `-(i + 1)`, `LayerElementNormal` flat
//!   normals `ByPolygonVertex`/`Direct`, `LayerElementMaterial` `AllSame`); an element without
//!   triangles is a `Null` model. A `Material` (`lambert`, sRGB `DiffuseColor`,
//!   `TransparencyFactor` = 1 - alpha) per distinct colour.
//! - Model names carry the GlobalId: `Name [GlobalId]` (the element's Name, else its class).
//!   Models also carry user properties (`U` flag; Unity hands them to
//!   `OnPostprocessGameObjectWithUserProperties`): `GlobalId`, `IfcClass`, `Storey` and, with
//!   a classification, `POI_Category`, `POI_Type`, `POI_PrimaryRoles`,
//!   `POI_ConditionalRoles` (role codes joined with `;`) and `AccessibilityStatus`.
//! - `Connections`: `OO` links (child, parent): storey -> root (0), element -> storey,
//!   geometry -> element, material -> element, node attribute -> storey.
//! - The footer: footer id, 4 zeros, zero padding to a multiple of 16 bytes (16 when already
//!   aligned), the version, 120 zeros and the 16-byte closing magic.
//!
//! Arrays are written uncompressed (encoding 0).

use std::path::Path;

use crate::scene::{prepare, Element, SceneInput};
use crate::ExportError;

/// The file magic: `Kaydara FBX Binary`, two spaces, NUL, then `0x1A 0x00`.
pub const MAGIC: &[u8; 23] = b"Kaydara FBX Binary  \x00\x1a\x00";
/// The version written: 7.4.
pub const VERSION: u32 = 7400;
/// The file id written in `FileId` (paired with [`CREATION_TIME`] and [`FOOTER_ID`]).
pub const FILE_ID: [u8; 16] = [
    0x28, 0xb3, 0x2a, 0xeb, 0xb6, 0x24, 0xcc, 0xc2, 0xbf, 0xc8, 0xb0, 0x2a, 0xa9, 0x2b, 0xfc, 0xf1,
];
/// The `CreationTime` written.
pub const CREATION_TIME: &str = "1970-01-01 10:00:00:000";
/// The first 16 bytes of the footer.
pub const FOOTER_ID: [u8; 16] = [
    0xfa, 0xbc, 0xab, 0x09, 0xd0, 0xc8, 0xd4, 0x66, 0xb1, 0x76, 0xfb, 0x83, 0x1c, 0xf7, 0x26, 0x7e,
];
/// The last 16 bytes of every binary FBX file.
pub const FOOTER_MAGIC: [u8; 16] = [
    0xf8, 0x5a, 0x8c, 0x6a, 0xde, 0xf5, 0xd9, 0x7e, 0xec, 0xe9, 0x0c, 0xe3, 0x75, 0x8f, 0x29, 0x0b,
];
/// A null record: ends a list of nested records, and the top-level list.
const NULL_RECORD: [u8; 13] = [0; 13];

/// One property of a record.
#[derive(Debug, Clone, PartialEq)]
pub enum Prop {
    /// `C`: a boolean, one byte.
    Bool(bool),
    /// `Y`: i16.
    I16(i16),
    /// `I`: i32.
    I32(i32),
    /// `L`: i64.
    I64(i64),
    /// `F`: f32.
    F32(f32),
    /// `D`: f64.
    F64(f64),
    /// `S`: a string (not NUL-terminated; may contain the `\0\x01` name separator).
    Str(String),
    /// `R`: raw bytes.
    Raw(Vec<u8>),
    /// `i`: an i32 array.
    I32s(Vec<i32>),
    /// `l`: an i64 array.
    I64s(Vec<i64>),
    /// `f`: an f32 array.
    F32s(Vec<f32>),
    /// `d`: an f64 array.
    F64s(Vec<f64>),
}

/// A node record: a name, a property tuple, nested records.
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    /// The record's name (at most 255 bytes).
    pub name: &'static str,
    /// Its properties.
    pub props: Vec<Prop>,
    /// Its nested records.
    pub children: Vec<Node>,
}

impl Node {
    /// A record with properties and no children.
    pub fn new(name: &'static str, props: Vec<Prop>) -> Node {
        Node {
            name,
            props,
            children: Vec::new(),
        }
    }

    /// A record with properties and children.
    pub fn with(name: &'static str, props: Vec<Prop>, children: Vec<Node>) -> Node {
        Node {
            name,
            props,
            children,
        }
    }
}

fn s(v: &str) -> Prop {
    Prop::Str(v.to_string())
}

/// `Name\0\x01Class`: how binary FBX writes an object's name and class. Control characters in
/// the name (which could fake the separator) become spaces.
fn object_name(name: &str, class: &str) -> Prop {
    let clean: String = name
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    Prop::Str(format!("{clean}\0\x01{class}"))
}

/// One `P` record of a `Properties70` block.
fn p(name: &str, ty: &str, label: &str, flags: &str, values: Vec<Prop>) -> Node {
    let mut props = vec![s(name), s(ty), s(label), s(flags)];
    props.extend(values);
    Node::new("P", props)
}

fn p_int(name: &str, v: i32) -> Node {
    p(name, "int", "Integer", "", vec![Prop::I32(v)])
}

fn p_double(name: &str, v: f64) -> Node {
    p(name, "double", "Number", "", vec![Prop::F64(v)])
}

fn p_vec(name: &str, ty: &str, v: [f64; 3]) -> Node {
    p(name, ty, "", "A", v.map(Prop::F64).to_vec())
}

fn p_user(name: &str, v: &str) -> Node {
    p(name, "KString", "", "U", vec![s(v)])
}

fn write_prop(out: &mut Vec<u8>, p: &Prop) {
    fn array<T>(out: &mut Vec<u8>, code: u8, values: &[T], put: impl Fn(&mut Vec<u8>, &T)) {
        out.push(code);
        out.extend_from_slice(&(values.len() as u32).to_le_bytes());
        out.extend_from_slice(&0u32.to_le_bytes()); // encoding: 0 = raw
        out.extend_from_slice(&(std::mem::size_of_val(values) as u32).to_le_bytes());
        for v in values {
            put(out, v);
        }
    }
    match p {
        Prop::Bool(v) => out.extend_from_slice(&[b'C', u8::from(*v)]),
        Prop::I16(v) => {
            out.push(b'Y');
            out.extend_from_slice(&v.to_le_bytes());
        }
        Prop::I32(v) => {
            out.push(b'I');
            out.extend_from_slice(&v.to_le_bytes());
        }
        Prop::I64(v) => {
            out.push(b'L');
            out.extend_from_slice(&v.to_le_bytes());
        }
        Prop::F32(v) => {
            out.push(b'F');
            out.extend_from_slice(&v.to_le_bytes());
        }
        Prop::F64(v) => {
            out.push(b'D');
            out.extend_from_slice(&v.to_le_bytes());
        }
        Prop::Str(v) => {
            out.push(b'S');
            out.extend_from_slice(&(v.len() as u32).to_le_bytes());
            out.extend_from_slice(v.as_bytes());
        }
        Prop::Raw(v) => {
            out.push(b'R');
            out.extend_from_slice(&(v.len() as u32).to_le_bytes());
            out.extend_from_slice(v);
        }
        Prop::I32s(v) => array(out, b'i', v, |o, x| o.extend_from_slice(&x.to_le_bytes())),
        Prop::I64s(v) => array(out, b'l', v, |o, x| o.extend_from_slice(&x.to_le_bytes())),
        Prop::F32s(v) => array(out, b'f', v, |o, x| o.extend_from_slice(&x.to_le_bytes())),
        Prop::F64s(v) => array(out, b'd', v, |o, x| o.extend_from_slice(&x.to_le_bytes())),
    }
}

fn offset(n: usize) -> [u8; 4] {
    u32::try_from(n)
        .expect("FBX 7.4 files are limited to 4 GiB")
        .to_le_bytes()
}

/// Appends `node` to `out` (which starts at file offset 0): end offset, property count,
/// property list length, name, properties, nested records and, when it has nested records or
/// no properties, a null record.
pub fn write_node(out: &mut Vec<u8>, node: &Node) {
    let start = out.len();
    out.extend_from_slice(&[0; 12]);
    let name = node.name.as_bytes();
    assert!(name.len() <= 255, "FBX record names have at most 255 bytes");
    out.push(name.len() as u8);
    out.extend_from_slice(name);
    let props_at = out.len();
    for p in &node.props {
        write_prop(out, p);
    }
    let props_len = out.len() - props_at;
    for c in &node.children {
        write_node(out, c);
    }
    if !node.children.is_empty() || node.props.is_empty() {
        out.extend_from_slice(&NULL_RECORD);
    }
    let end = offset(out.len());
    out[start..start + 4].copy_from_slice(&end);
    out[start + 4..start + 8].copy_from_slice(&offset(node.props.len()));
    out[start + 8..start + 12].copy_from_slice(&offset(props_len));
}

/// A whole file: header, `nodes`, the top-level null record and the footer.
pub fn write_document(nodes: &[Node]) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    for n in nodes {
        write_node(&mut out, n);
    }
    out.extend_from_slice(&NULL_RECORD);
    out.extend_from_slice(&FOOTER_ID);
    out.extend_from_slice(&[0; 4]);
    let pad = match out.len() % 16 {
        0 => 16,
        r => 16 - r,
    };
    out.resize(out.len() + pad, 0);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.extend_from_slice(&[0; 120]);
    out.extend_from_slice(&FOOTER_MAGIC);
    out
}

fn header_extension(creator: &str) -> Vec<Node> {
    let time = [
        ("Version", 1000),
        ("Year", 1970),
        ("Month", 1),
        ("Day", 1),
        ("Hour", 10),
        ("Minute", 0),
        ("Second", 0),
        ("Millisecond", 0),
    ]
    .into_iter()
    .map(|(k, v)| Node::new(k, vec![Prop::I32(v)]))
    .collect();
    let meta = [
        "Title", "Subject", "Author", "Keywords", "Revision", "Comment",
    ]
    .into_iter()
    .map(|k| Node::new(k, vec![s("")]));
    let meta: Vec<Node> = std::iter::once(Node::new("Version", vec![Prop::I32(100)]))
        .chain(meta)
        .collect();
    vec![
        Node::with(
            "FBXHeaderExtension",
            vec![],
            vec![
                Node::new("FBXHeaderVersion", vec![Prop::I32(1003)]),
                Node::new("FBXVersion", vec![Prop::I32(VERSION as i32)]),
                Node::new("EncryptionType", vec![Prop::I32(0)]),
                Node::with("CreationTimeStamp", vec![], time),
                Node::new("Creator", vec![s(creator)]),
                Node::with(
                    "SceneInfo",
                    vec![object_name("GlobalInfo", "SceneInfo"), s("UserData")],
                    vec![
                        Node::new("Type", vec![s("UserData")]),
                        Node::new("Version", vec![Prop::I32(100)]),
                        Node::with("MetaData", vec![], meta),
                        Node::with(
                            "Properties70",
                            vec![],
                            vec![
                                p(
                                    "Original|ApplicationVendor",
                                    "KString",
                                    "",
                                    "",
                                    vec![s("poinav")],
                                ),
                                p(
                                    "Original|ApplicationName",
                                    "KString",
                                    "",
                                    "",
                                    vec![s("poinav")],
                                ),
                                p(
                                    "Original|ApplicationVersion",
                                    "KString",
                                    "",
                                    "",
                                    vec![s(env!("CARGO_PKG_VERSION"))],
                                ),
                            ],
                        ),
                    ],
                ),
            ],
        ),
        Node::new("FileId", vec![Prop::Raw(FILE_ID.to_vec())]),
        Node::new("CreationTime", vec![s(CREATION_TIME)]),
        Node::new("Creator", vec![s(creator)]),
    ]
}

fn global_settings() -> Node {
    Node::with(
        "GlobalSettings",
        vec![],
        vec![
            Node::new("Version", vec![Prop::I32(1000)]),
            Node::with(
                "Properties70",
                vec![],
                vec![
                    p_int("UpAxis", 1),
                    p_int("UpAxisSign", 1),
                    p_int("FrontAxis", 2),
                    p_int("FrontAxisSign", 1),
                    p_int("CoordAxis", 0),
                    p_int("CoordAxisSign", 1),
                    p_int("OriginalUpAxis", 2),
                    p_int("OriginalUpAxisSign", 1),
                    p_double("UnitScaleFactor", 100.0),
                    p_double("OriginalUnitScaleFactor", 100.0),
                    p(
                        "AmbientColor",
                        "ColorRGB",
                        "Color",
                        "",
                        vec![Prop::F64(0.0); 3],
                    ),
                    p(
                        "DefaultCamera",
                        "KString",
                        "",
                        "",
                        vec![s("Producer Perspective")],
                    ),
                    p("TimeMode", "enum", "", "", vec![Prop::I32(11)]),
                    p("TimeSpanStart", "KTime", "Time", "", vec![Prop::I64(0)]),
                    p(
                        "TimeSpanStop",
                        "KTime",
                        "Time",
                        "",
                        vec![Prop::I64(46_186_158_000)],
                    ),
                    p_double("CustomFrameRate", -1.0),
                ],
            ),
        ],
    )
}

/// Objects and connections being collected, with their ids.
struct Builder {
    next_id: i64,
    objects: Vec<Node>,
    connections: Vec<Node>,
    counts: [usize; 4], // Model, Geometry, Material, NodeAttribute
}

impl Builder {
    fn id(&mut self) -> i64 {
        self.next_id += 1;
        self.next_id
    }

    fn connect(&mut self, child: i64, parent: i64) {
        self.connections.push(Node::new(
            "C",
            vec![s("OO"), Prop::I64(child), Prop::I64(parent)],
        ));
    }

    /// A `Model` of `kind` (`Mesh` or `Null`) named `name`, at `translation`, with user
    /// properties; a `Null` gets its node attribute. Returns its id.
    fn model(
        &mut self,
        name: &str,
        kind: &str,
        translation: [f64; 3],
        user: &[(&str, String)],
    ) -> i64 {
        let id = self.id();
        let mut props = vec![
            p_vec("Lcl Translation", "Lcl Translation", translation),
            p_int("DefaultAttributeIndex", 0),
            p("InheritType", "enum", "", "", vec![Prop::I32(1)]),
        ];
        props.extend(user.iter().map(|(k, v)| p_user(k, v)));
        self.objects.push(Node::with(
            "Model",
            vec![Prop::I64(id), object_name(name, "Model"), s(kind)],
            vec![
                Node::new("Version", vec![Prop::I32(232)]),
                Node::with("Properties70", vec![], props),
                Node::new("MultiLayer", vec![Prop::I32(0)]),
                Node::new("MultiTake", vec![Prop::I32(0)]),
                Node::new("Shading", vec![Prop::Bool(true)]),
                Node::new("Culling", vec![s("CullingOff")]),
            ],
        ));
        self.counts[0] += 1;
        if kind == "Null" {
            let attr = self.id();
            self.objects.push(Node::with(
                "NodeAttribute",
                vec![Prop::I64(attr), object_name("", "NodeAttribute"), s("Null")],
                vec![Node::new("TypeFlags", vec![s("Null")])],
            ));
            self.counts[3] += 1;
            self.connect(attr, id);
        }
        id
    }

    /// The `Geometry` of `e` (which has triangles). Returns its id.
    fn geometry(&mut self, e: &Element<'_>) -> i64 {
        let id = self.id();
        let vertices: Vec<f64> = e
            .positions
            .iter()
            .flatten()
            .map(|&v| f64::from(v))
            .collect();
        let polygons: Vec<i32> = e
            .triangles
            .iter()
            .flat_map(|&[a, b, c]| [a as i32, b as i32, !(c as i32)])
            .collect();
        let normals: Vec<f64> = e
            .normals
            .iter()
            .flat_map(|n| std::iter::repeat_n(n, 3))
            .flatten()
            .map(|&v| f64::from(v))
            .collect();
        let layer_element = |ty: &str| {
            Node::with(
                "LayerElement",
                vec![],
                vec![
                    Node::new("Type", vec![s(ty)]),
                    Node::new("TypedIndex", vec![Prop::I32(0)]),
                ],
            )
        };
        self.objects.push(Node::with(
            "Geometry",
            vec![
                Prop::I64(id),
                object_name(&e.label_with_guid(), "Geometry"),
                s("Mesh"),
            ],
            vec![
                Node::new("Properties70", vec![]),
                Node::new("GeometryVersion", vec![Prop::I32(124)]),
                Node::new("Vertices", vec![Prop::F64s(vertices)]),
                Node::new("PolygonVertexIndex", vec![Prop::I32s(polygons)]),
                Node::with(
                    "LayerElementNormal",
                    vec![Prop::I32(0)],
                    vec![
                        Node::new("Version", vec![Prop::I32(101)]),
                        Node::new("Name", vec![s("")]),
                        Node::new("MappingInformationType", vec![s("ByPolygonVertex")]),
                        Node::new("ReferenceInformationType", vec![s("Direct")]),
                        Node::new("Normals", vec![Prop::F64s(normals)]),
                    ],
                ),
                Node::with(
                    "LayerElementMaterial",
                    vec![Prop::I32(0)],
                    vec![
                        Node::new("Version", vec![Prop::I32(101)]),
                        Node::new("Name", vec![s("")]),
                        Node::new("MappingInformationType", vec![s("AllSame")]),
                        Node::new("ReferenceInformationType", vec![s("IndexToDirect")]),
                        Node::new("Materials", vec![Prop::I32s(vec![0])]),
                    ],
                ),
                Node::with(
                    "Layer",
                    vec![Prop::I32(0)],
                    vec![
                        Node::new("Version", vec![Prop::I32(100)]),
                        layer_element("LayerElementNormal"),
                        layer_element("LayerElementMaterial"),
                    ],
                ),
            ],
        ));
        self.counts[1] += 1;
        id
    }

    /// A lambert `Material` of sRGB `rgba`. Returns its id.
    fn material(&mut self, name: &str, rgba: [f32; 4]) -> i64 {
        let id = self.id();
        let [r, g, b, a] = rgba.map(f64::from);
        self.objects.push(Node::with(
            "Material",
            vec![Prop::I64(id), object_name(name, "Material"), s("")],
            vec![
                Node::new("Version", vec![Prop::I32(102)]),
                Node::new("ShadingModel", vec![s("lambert")]),
                Node::new("MultiLayer", vec![Prop::I32(0)]),
                Node::with(
                    "Properties70",
                    vec![],
                    vec![
                        p_vec("EmissiveColor", "Color", [0.0; 3]),
                        p_vec("AmbientColor", "Color", [0.0; 3]),
                        p_vec("DiffuseColor", "Color", [r, g, b]),
                        p("DiffuseFactor", "Number", "", "A", vec![Prop::F64(1.0)]),
                        p_vec("TransparentColor", "Color", [1.0; 3]),
                        p(
                            "TransparencyFactor",
                            "Number",
                            "",
                            "A",
                            vec![Prop::F64(1.0 - a)],
                        ),
                        p_double("Opacity", a),
                    ],
                ),
            ],
        ));
        self.counts[2] += 1;
        id
    }
}

/// The FBX node records of `scene` (everything between the header and the footer).
pub fn to_fbx_nodes(scene: &SceneInput<'_>) -> Vec<Node> {
    let prepared = prepare(scene);
    let creator = crate::glb::generator();
    let mut b = Builder {
        next_id: 1_000_000,
        objects: Vec::new(),
        connections: Vec::new(),
        counts: [0; 4],
    };
    let materials: Vec<i64> = prepared
        .materials
        .iter()
        .map(|m| b.material(&m.name, m.rgba))
        .collect();
    for g in &prepared.groups {
        let mut user = vec![];
        let mut name = g.label.clone();
        if let Some(st) = g.storey {
            user.push(("IfcClass", "IfcBuildingStorey".to_string()));
            if let Some(guid) = st.global_id.as_ref().filter(|x| !x.is_empty()) {
                user.push(("GlobalId", guid.clone()));
                if g.label != *guid {
                    name = format!("{} [{guid}]", g.label);
                }
            }
        }
        let group = b.model(&name, "Null", g.origin.to_array(), &user);
        b.connect(group, 0);
        for &i in &g.elements {
            let e = &prepared.elements[i];
            let mut user = vec![
                ("GlobalId", e.source.global_id.clone()),
                ("IfcClass", e.source.class.clone()),
                ("Storey", e.storey_name.unwrap_or_default().to_string()),
            ];
            user.extend(e.poi_pairs());
            let kind = if e.triangles.is_empty() {
                "Null"
            } else {
                "Mesh"
            };
            let model = b.model(&e.label_with_guid(), kind, e.translation.to_array(), &user);
            b.connect(model, group);
            if !e.triangles.is_empty() {
                let geometry = b.geometry(e);
                b.connect(geometry, model);
                b.connect(materials[e.material], model);
            }
        }
    }
    let [models, geometries, mats, attrs] = b.counts;
    let object_type = |ty: &str, n: usize| {
        Node::with(
            "ObjectType",
            vec![s(ty)],
            vec![Node::new("Count", vec![Prop::I32(n as i32)])],
        )
    };
    let mut definitions = vec![
        Node::new("Version", vec![Prop::I32(100)]),
        Node::new(
            "Count",
            vec![Prop::I32((1 + models + geometries + mats + attrs) as i32)],
        ),
        object_type("GlobalSettings", 1),
    ];
    for (ty, n) in [
        ("Model", models),
        ("NodeAttribute", attrs),
        ("Geometry", geometries),
        ("Material", mats),
    ] {
        if n > 0 {
            definitions.push(object_type(ty, n));
        }
    }
    let mut nodes = header_extension(&creator);
    nodes.push(global_settings());
    nodes.push(Node::with(
        "Documents",
        vec![],
        vec![
            Node::new("Count", vec![Prop::I32(1)]),
            Node::with(
                "Document",
                vec![Prop::I64(1_000_000), s("Scene"), s("Scene")],
                vec![
                    Node::with(
                        "Properties70",
                        vec![],
                        vec![
                            p("SourceObject", "object", "", "", vec![]),
                            p("ActiveAnimStackName", "KString", "", "", vec![s("")]),
                        ],
                    ),
                    Node::new("RootNode", vec![Prop::I64(0)]),
                ],
            ),
        ],
    ));
    nodes.push(Node::new("References", vec![]));
    nodes.push(Node::with("Definitions", vec![], definitions));
    nodes.push(Node::with("Objects", vec![], b.objects));
    nodes.push(Node::with("Connections", vec![], b.connections));
    nodes.push(Node::with(
        "Takes",
        vec![],
        vec![Node::new("Current", vec![s("")])],
    ));
    nodes
}

/// The binary FBX 7.4 bytes of `scene`.
///
/// # Panics
/// When the file would exceed 4 GiB, the limit of FBX 7.4's 32-bit offsets.
pub fn to_fbx(scene: &SceneInput<'_>) -> Vec<u8> {
    write_document(&to_fbx_nodes(scene))
}

/// Writes the FBX of `scene` to `path` atomically.
pub fn write_fbx(path: &Path, scene: &SceneInput<'_>) -> Result<(), ExportError> {
    poinav_io::write_atomic(path, &to_fbx(scene)).map_err(|e| ExportError::Write {
        path: path.display().to_string(),
        message: e.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn u32_at(b: &[u8], at: usize) -> u32 {
        u32::from_le_bytes(b[at..at + 4].try_into().unwrap())
    }

    #[test]
    fn header_and_footer_bytes() {
        let b = write_document(&[]);
        assert_eq!(&b[..21], b"Kaydara FBX Binary  \0");
        assert_eq!(&b[21..23], &[0x1a, 0x00]);
        assert_eq!(u32_at(&b, 23), 7400);
        assert_eq!(&b[27..40], &[0u8; 13]);
        assert_eq!(&b[40..56], &FOOTER_ID);
        assert_eq!(&b[56..60], &[0; 4]);
        // 60 -> padded to 64.
        assert_eq!(&b[60..64], &[0; 4]);
        assert_eq!(u32_at(&b, 64), 7400);
        assert_eq!(&b[68..188], &[0u8; 120]);
        assert_eq!(&b[188..], &FOOTER_MAGIC);
        assert_eq!(b.len(), 204);
        // The version starts on a 16-byte boundary.
        assert_eq!((b.len() - 16 - 120 - 4) % 16, 0);
    }

    #[test]
    fn footer_padding_is_sixteen_when_already_aligned() {
        // Header 27, one record of 13 + len + 5 bytes, null record 13, footer id 16, 4 zeros:
        // some name length puts the padding start on a multiple of 16.
        for len in 1..=16usize {
            let name: &'static str = &"ABCDEFGHIJKLMNOP"[..len];
            let b = write_document(&[Node::new(name, vec![Prop::I32(1)])]);
            let before_pad = 27 + 13 + len + 5 + 13 + 16 + 4;
            let pad = b.len() - before_pad - 4 - 120 - 16;
            assert!((1..=16).contains(&pad));
            assert_eq!((before_pad + pad) % 16, 0);
            if before_pad % 16 == 0 {
                assert_eq!(pad, 16);
            }
        }
    }

    #[test]
    fn records_have_end_offsets_counts_and_null_records() {
        let nodes = [Node::with(
            "Top",
            vec![Prop::I32(7), s("ab")],
            vec![
                Node::new("Leaf", vec![Prop::F64s(vec![1.0, 2.0]), Prop::Bool(true)]),
                Node::new("Empty", vec![]),
            ],
        )];
        let b = write_document(&nodes);
        // Top at 27: end, count 2, property bytes (1+4)+(1+4+2) = 12, name.
        let top = 27;
        assert_eq!(u32_at(&b, top + 4), 2);
        assert_eq!(u32_at(&b, top + 8), 12);
        assert_eq!(b[top + 12], 3);
        assert_eq!(&b[top + 13..top + 16], b"Top");
        assert_eq!(b[top + 16], b'I');
        assert_eq!(u32_at(&b, top + 17), 7);
        assert_eq!(b[top + 21], b'S');
        assert_eq!(u32_at(&b, top + 22), 2);
        let leaf = top + 16 + 12;
        assert_eq!(&b[leaf + 13..leaf + 17], b"Leaf");
        // Array: 'd', count 2, encoding 0, 16 bytes, data; then 'C' 1.
        let arr = leaf + 17;
        assert_eq!(b[arr], b'd');
        assert_eq!(u32_at(&b, arr + 1), 2);
        assert_eq!(u32_at(&b, arr + 5), 0);
        assert_eq!(u32_at(&b, arr + 9), 16);
        assert_eq!(
            f64::from_le_bytes(b[arr + 13..arr + 21].try_into().unwrap()),
            1.0
        );
        assert_eq!(&b[arr + 29..arr + 31], &[b'C', 1]);
        let leaf_end = u32_at(&b, leaf) as usize;
        assert_eq!(
            leaf_end,
            arr + 31,
            "a leaf with properties has no null record"
        );
        let empty = leaf_end;
        let empty_end = u32_at(&b, empty) as usize;
        assert_eq!(
            empty_end,
            empty + 13 + 5 + 13,
            "an empty record ends with one"
        );
        let top_end = u32_at(&b, top) as usize;
        assert_eq!(top_end, empty_end + 13);
        assert_eq!(&b[empty_end..top_end], &[0u8; 13]);
        // Then the top-level null record and the footer.
        assert_eq!(&b[top_end..top_end + 13], &[0u8; 13]);
        assert_eq!(&b[top_end + 13..top_end + 29], &FOOTER_ID);
    }

    #[test]
    fn object_names_use_the_binary_separator() {
        assert_eq!(
            object_name("Wall\0x", "Model"),
            Prop::Str("Wall x\0\x01Model".into())
        );
    }
}
