//! The scene file's JSON Schema (`docs/src/reference/scene-file.schema.json`, from the
//! serde types through schemars) and its key reference (`scene-file-keys.md`, from the
//! schema), both generated and checked in; the bundled scenes name the schema on their
//! first line, so that editors complete and check them.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::PathBuf;

use serde_json::Value;

use super::generated;
use crate::common;

const SCHEMA: &str = "docs/src/reference/scene-file.schema.json";
const KEYS: &str = "docs/src/reference/scene-file-keys.md";
/// The first line of every bundled scene (relative to `assets/scenes/`).
const SCHEMA_LINE: &str = "#:schema ../../docs/src/reference/scene-file.schema.json";

/// The definition a `$ref` names.
fn definition<'a>(root: &'a Value, reference: &str) -> &'a Value {
    let name = reference.trim_start_matches("#/definitions/");
    &root["definitions"][name]
}

/// A description as one Markdown table cell: rustdoc links as code, lines joined.
fn cell(text: &str) -> String {
    let text = text
        .replace("[`", "`")
        .replace("`]", "`")
        .replace('|', "\\|");
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The TOML type of a schema: `number`, `[x, y, z] (numbers)`, `"a" | "b"`, ….
fn type_of(root: &Value, schema: &Value) -> String {
    if let Some(r) = schema["$ref"].as_str() {
        return type_of(root, definition(root, r));
    }
    if let Some(all) = schema["allOf"].as_array() {
        return type_of(root, &all[0]);
    }
    if let Some(c) = schema.get("const") {
        return c.to_string();
    }
    for key in ["oneOf", "anyOf"] {
        if let Some(options) = schema[key].as_array() {
            let kinds: Vec<String> = options
                .iter()
                .map(|o| type_of(root, o))
                .filter(|t| !t.is_empty())
                .collect();
            return kinds.join(" \\| ");
        }
    }
    if let Some(values) = schema["enum"].as_array() {
        let values: Vec<String> = values.iter().map(Value::to_string).collect();
        return values.join(" \\| ");
    }
    let kinds: Vec<&str> = match &schema["type"] {
        Value::String(t) => vec![t.as_str()],
        Value::Array(ts) => ts.iter().filter_map(Value::as_str).collect(),
        _ => vec![],
    };
    let kinds: Vec<String> = kinds
        .into_iter()
        .filter(|k| *k != "null")
        .map(|k| match k {
            "array" => {
                let item = type_of(root, &schema["items"]);
                match (schema["minItems"].as_u64(), schema["maxItems"].as_u64()) {
                    (Some(a), Some(b)) if a == b => format!("{b} × {item}"),
                    _ => format!("list of {item}"),
                }
            }
            "object"
                if schema
                    .get("additionalProperties")
                    .is_some_and(Value::is_object) =>
            {
                format!(
                    "table of {}",
                    type_of(root, &schema["additionalProperties"])
                )
            }
            "integer" if schema["minimum"].as_f64() == Some(0.0) => "integer ≥ 0".into(),
            other => other.to_string(),
        })
        .collect();
    kinds.join(" \\| ")
}

/// The allowed values of an enumeration with their meanings, if `schema` is one.
fn values_of(root: &Value, schema: &Value) -> Vec<(String, String)> {
    if let Some(r) = schema["$ref"].as_str() {
        return values_of(root, definition(root, r));
    }
    // An optional enumeration: `anyOf` its definition and null.
    for key in ["allOf", "anyOf"] {
        if let Some(first) = schema[key].as_array().and_then(|a| a.first()) {
            return values_of(root, first);
        }
    }
    let Some(options) = schema["oneOf"].as_array() else {
        return Vec::new();
    };
    options
        .iter()
        .filter_map(|o| {
            let value = o.get("const")?.to_string();
            Some((value, cell(o["description"].as_str().unwrap_or(""))))
        })
        .collect()
}

/// The table a root key holds, and how it is written (`[[model]]` or `[display]`).
fn table_of<'a>(root: &'a Value, key: &str, schema: &'a Value) -> (String, &'a Value) {
    if schema["type"] == "array" {
        let items = &schema["items"];
        let r = items["$ref"].as_str().expect("an array of tables");
        (format!("[[{key}]]"), definition(root, r))
    } else {
        let r = schema["$ref"]
            .as_str()
            .or_else(|| schema["allOf"][0]["$ref"].as_str())
            .or_else(|| schema["anyOf"][0]["$ref"].as_str())
            .expect("a table");
        (format!("[{key}]"), definition(root, r))
    }
}

/// The key reference page.
fn keys_page(root: &Value) -> String {
    let mut out = String::from(
        "# Scene file keys\n\n<!-- Generated from the serde types in src/scene/ (through \
         the JSON Schema) by scripts/gen-docs.sh; edit their doc comments, not this page. \
         -->\n\n",
    );
    out.push_str(
        "Every table and key that a scene file may hold, with its type, default and meaning, \
         generated from the code that reads it. A key not listed here is an error that names \
         it. Units: metres, degrees, lux, candela. The same as a JSON Schema, for editors: \
         [`scene-file.schema.json`](scene-file.schema.json) (start a scene file with \
         `#:schema PATH` to have Taplo or Even Better TOML complete and check it). How the \
         keys work together: [the scene file](scene-file.md).\n\n",
    );
    let props = root["properties"].as_object().unwrap();
    let required: Vec<&str> = root["required"]
        .as_array()
        .map(|r| r.iter().filter_map(Value::as_str).collect())
        .unwrap_or_default();
    for (key, schema) in props {
        let (heading, table) = table_of(root, key, schema);
        writeln!(out, "## `{heading}`\n").unwrap();
        let about = schema["description"]
            .as_str()
            .or(table["description"].as_str())
            .unwrap_or("");
        writeln!(out, "{}\n", cell(about)).unwrap();
        if required.contains(&key.as_str()) {
            out.push_str("Required.\n\n");
        }
        out.push_str("| key | type | default | meaning |\n|---|---|---|---|\n");
        let needed: Vec<&str> = table["required"]
            .as_array()
            .map(|r| r.iter().filter_map(Value::as_str).collect())
            .unwrap_or_default();
        let mut enums = Vec::new();
        for (name, field) in table["properties"].as_object().unwrap() {
            let default = match field.get("default") {
                Some(d) if !d.is_null() => format!("`{d}`"),
                _ if needed.contains(&name.as_str()) => "required".into(),
                _ => "—".into(),
            };
            writeln!(
                out,
                "| `{name}` | {} | {default} | {} |",
                type_of(root, field),
                cell(field["description"].as_str().unwrap_or(""))
            )
            .unwrap();
            let values = values_of(root, field);
            if !values.is_empty() {
                enums.push((name.clone(), values));
            }
        }
        out.push('\n');
        for (name, values) in enums {
            writeln!(out, "`{name}`:\n").unwrap();
            for (value, meaning) in values {
                writeln!(out, "- `{value}`: {meaning}").unwrap();
            }
            out.push('\n');
        }
    }
    out.trim_end().to_string() + "\n"
}

#[test]
fn the_scene_file_schema_and_keys_are_what_the_code_generates() {
    let schema = goniolight::scene::file::json_schema();
    let mut want = BTreeMap::new();
    let text = serde_json::to_string_pretty(&schema).unwrap() + "\n";
    want.insert(PathBuf::from(SCHEMA), text.into_bytes());
    want.insert(PathBuf::from(KEYS), keys_page(&schema).into_bytes());
    generated::compare_or_bless(&want, &[]);
}

#[test]
fn the_key_reference_lists_every_key_of_the_types() {
    // Spot checks against keys the scene files use, from each table.
    let page = keys_page(&goniolight::scene::file::json_schema());
    for needle in [
        "## `[[model]]`",
        "## `[[luminaire]]`",
        "## `[camera]`",
        "## `[display]`",
        "## `[[grid]]`",
        "## `[calc]`",
        "## `[[observer]]`",
        "## `[[material]]`",
        "| `multiplier` | number | `1.0` |",
        "| `position` | 3 × number | required |",
        "| `maintenance_factor` | number | `1.0` |",
        "- `\"catmull-rom\"`: ",
        "| `spacing` | number \\| string | `\"en12464\"` |",
    ] {
        assert!(
            page.contains(needle),
            "{needle:?} missing from the key reference"
        );
    }
}

#[test]
fn every_bundled_scene_names_the_schema() {
    let scenes = common::root().join("assets/scenes");
    let path = scenes.join(SCHEMA_LINE.trim_start_matches("#:schema "));
    assert!(path.exists(), "{} does not exist", path.display());
    let files = common::files_with(&scenes, &["toml"]);
    assert!(files.len() >= 10);
    for file in files {
        let text = std::fs::read_to_string(scenes.join(&file)).unwrap();
        assert_eq!(
            text.lines().next(),
            Some(SCHEMA_LINE),
            "assets/scenes/{}: the first line names the schema",
            file.display()
        );
    }
}
