//! Generates `crates/poinav-ifc/src/schema/<schema>.rs` from the schema facts in `shared/schema/*.json`.
//!
//! Entities are emitted sorted by their upper-case STEP name so the reader can binary-search them;
//! each entity lists only its own attributes and inverses (inherited ones are found through the
//! supertype chain), plus the absolute positions of inherited attributes it redefines as DERIVE.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde_json::Value;

/// Whether to write the generated files or only compare them with what is committed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    Write,
    Check,
}

/// The schemas poinav reads: (file stem in shared/schema, generated module name).
pub const SCHEMAS: [(&str, &str); 3] = [
    ("IFC2X3", "ifc2x3"),
    ("IFC4", "ifc4"),
    ("IFC4X3_ADD2", "ifc4x3_add2"),
];

pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

pub fn shared_dir() -> PathBuf {
    match std::env::var_os("POINAV_SHARED") {
        Some(dir) => PathBuf::from(dir),
        None => workspace_root().join("../shared"),
    }
}

pub fn run(mode: Mode) -> Result<(), String> {
    let out_dir = workspace_root().join("crates/poinav-ifc/src/schema");
    let mut stale = Vec::new();
    for (stem, module) in SCHEMAS {
        let src = shared_dir().join("schema").join(format!("{stem}.json"));
        let text = std::fs::read_to_string(&src).map_err(|e| format!("{}: {e}", src.display()))?;
        let json: Value =
            serde_json::from_str(&text).map_err(|e| format!("{}: {e}", src.display()))?;
        let code = generate(stem, &json)?;
        let dst = out_dir.join(format!("{module}.rs"));
        let current = std::fs::read_to_string(&dst).unwrap_or_default();
        if current == code {
            continue;
        }
        match mode {
            Mode::Write => {
                std::fs::write(&dst, code).map_err(|e| format!("{}: {e}", dst.display()))?
            }
            Mode::Check => stale.push(dst.display().to_string()),
        }
    }
    if stale.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "generated files are stale, run `cargo xtask codegen`: {}",
            stale.join(", ")
        ))
    }
}

struct Entity<'a> {
    name: &'a str,
    supertype: Option<&'a str>,
    is_abstract: bool,
    attrs: Vec<(&'a str, &'a str, bool, bool)>,
    inverses: Vec<(&'a str, &'a str, &'a str)>,
}

fn str_field<'a>(v: &'a Value, key: &str, ctx: &str) -> Result<&'a str, String> {
    v.get(key)
        .and_then(Value::as_str)
        .ok_or_else(|| format!("{ctx}: missing string `{key}`"))
}

fn parse_entities(json: &Value) -> Result<BTreeMap<String, Entity<'_>>, String> {
    let entities = json
        .get("entities")
        .and_then(Value::as_object)
        .ok_or("no `entities` object")?;
    let mut out = BTreeMap::new();
    for (name, e) in entities {
        let mut attrs = Vec::new();
        for a in e
            .get("attributes")
            .and_then(Value::as_array)
            .ok_or_else(|| format!("{name}: no attributes"))?
        {
            attrs.push((
                str_field(a, "name", name)?,
                str_field(a, "type", name).unwrap_or("?"),
                a.get("optional").and_then(Value::as_bool).unwrap_or(false),
                a.get("derived").and_then(Value::as_bool).unwrap_or(false),
            ));
        }
        let mut inverses = Vec::new();
        for i in e
            .get("inverses")
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
        {
            inverses.push((
                str_field(i, "name", name)?,
                str_field(i, "entity", name)?,
                str_field(i, "attribute", name)?,
            ));
        }
        out.insert(
            name.to_ascii_uppercase(),
            Entity {
                name,
                supertype: e.get("supertype").and_then(Value::as_str),
                is_abstract: e.get("abstract").and_then(Value::as_bool).unwrap_or(false),
                attrs,
                inverses,
            },
        );
    }
    Ok(out)
}

fn rust_str(s: &str) -> String {
    format!("{s:?}")
}

pub fn generate(stem: &str, json: &Value) -> Result<String, String> {
    let entities = parse_entities(json)?;
    let index: BTreeMap<&str, usize> = entities
        .keys()
        .enumerate()
        .map(|(i, k)| (k.as_str(), i))
        .collect();
    let by_name: BTreeMap<&str, &Entity<'_>> = entities.values().map(|e| (e.name, e)).collect();
    let idx_of = |name: &str| -> Result<usize, String> {
        index
            .get(name.to_ascii_uppercase().as_str())
            .copied()
            .ok_or_else(|| format!("unknown entity {name}"))
    };

    let mut out = String::new();
    writeln!(out, "//! IFC schema tables for {stem}, generated by `cargo xtask codegen` from shared/schema/{stem}.json. Do not edit.").unwrap();
    writeln!(out).unwrap();
    writeln!(out, "use super::{{AttrDef, EntityDef, InverseDef}};").unwrap();
    writeln!(out).unwrap();
    writeln!(out, "pub(crate) static ENTITIES: &[EntityDef] = &[").unwrap();
    for (upper, e) in &entities {
        let sup = match e.supertype {
            Some(s) => {
                let parent = by_name
                    .get(s)
                    .ok_or_else(|| format!("{}: unknown supertype {s}", e.name))?;
                Some((idx_of(s)?, parent))
            }
            None => None,
        };
        let offset = sup.map_or(0, |(_, p)| p.attrs.len());
        if let Some((_, p)) = sup {
            for (i, pa) in p.attrs.iter().enumerate() {
                if e.attrs.get(i).map(|a| a.0) != Some(pa.0) {
                    return Err(format!(
                        "{}: inherited attribute {} out of order",
                        e.name, pa.0
                    ));
                }
            }
        }
        let own_attrs: Vec<String> = e.attrs[offset..]
            .iter()
            .map(|(n, t, opt, _)| {
                format!(
                    "AttrDef {{ name: {}, ty: {}, optional: {opt} }}",
                    rust_str(n),
                    rust_str(t)
                )
            })
            .collect();
        let derived: Vec<String> = e
            .attrs
            .iter()
            .enumerate()
            .filter(|(_, a)| a.3)
            .map(|(i, _)| i.to_string())
            .collect();
        let inherited_inv: Vec<&str> = sup
            .map(|(_, p)| p.inverses.iter().map(|i| i.0).collect())
            .unwrap_or_default();
        let mut own_inv = Vec::new();
        for (n, ent, attr) in &e.inverses {
            if inherited_inv.contains(n) {
                continue;
            }
            own_inv.push(format!(
                "InverseDef {{ name: {}, entity: {}, attribute: {} }}",
                rust_str(n),
                idx_of(ent)?,
                rust_str(attr)
            ));
        }
        writeln!(
            out,
            "    EntityDef {{ name: {}, upper: {}, supertype: {}, is_abstract: {}, attr_offset: {offset}, attrs: &[{}], derived: &[{}], inverses: &[{}] }},",
            rust_str(e.name),
            rust_str(upper),
            sup.map_or("None".to_string(), |(i, _)| format!("Some({i})")),
            e.is_abstract,
            own_attrs.join(", "),
            derived.join(", "),
            own_inv.join(", "),
        )
        .unwrap();
    }
    writeln!(out, "];").unwrap();
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_schema_tables_are_up_to_date() {
        run(Mode::Check).unwrap();
    }
}
