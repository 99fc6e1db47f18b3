//! Where every key of a TOML document is: a map from dotted key paths (`sphere[2].radius`)
//! to the byte spans of the key and its value, and back from a byte offset to the innermost
//! key path that covers it.
//!
//! The typed scene structs are deserialized with serde, whose errors carry a span but no key
//! path; and the core's validation errors name an item and a field but carry no span. This
//! index connects the two: it is built from a generic, [`Spanned`]-annotated parse of the same
//! text, so both kinds of error can be reported as `line:column` plus the key.
//!
//! Only values carry spans here (toml's datetimes cannot be read with spanned keys), so an
//! error is placed at the offending value, which sits on its key's line.

use serde::de::{Deserialize, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use std::fmt;
use std::ops::Range;
use toml::Spanned;

/// One key (or array element) of the document.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct KeyEntry {
    /// The dotted path, arrays indexed from 0: `camera.look_at`, `sphere[2]`, `light[0].color[1]`.
    pub path: String,
    /// The span of the value.
    pub value: Range<usize>,
    /// What the value is: `"table"`, `"array"`, `"datetime"` or `"value"` (anything else).
    pub kind: &'static str,
}

/// Every key path of a document with its spans, in document-tree order.
#[derive(Clone, Debug, Default)]
pub struct KeyIndex {
    entries: Vec<KeyEntry>,
}

impl KeyIndex {
    /// Parses `text` as TOML and indexes every key. Fails with toml's own error (and span) if
    /// the text is not TOML.
    pub fn parse(text: &str) -> Result<Self, toml::de::Error> {
        let root: Node = toml::from_str(text)?;
        let mut index = KeyIndex::default();
        if let Node::Table(children) = root {
            index.add_table("", children);
        }
        Ok(index)
    }

    fn add_table(&mut self, prefix: &str, children: Vec<(String, Spanned<Node>)>) {
        for (key, value) in children {
            let path = if prefix.is_empty() {
                key
            } else {
                format!("{prefix}.{key}")
            };
            self.add(path, value);
        }
    }

    fn add(&mut self, path: String, value: Spanned<Node>) {
        let kind = match value.get_ref() {
            Node::Table(_) => "table",
            Node::Array(_) => "array",
            Node::Datetime => "datetime",
            Node::Leaf => "value",
        };
        self.entries.push(KeyEntry {
            path: path.clone(),
            value: value.span(),
            kind,
        });
        match value.into_inner() {
            Node::Table(children) => self.add_table(&path, children),
            Node::Array(items) => {
                for (i, item) in items.into_iter().enumerate() {
                    self.add(format!("{path}[{i}]"), item);
                }
            }
            Node::Leaf | Node::Datetime => {}
        }
    }

    /// The entry for an exact key path, if the document has it.
    pub fn get(&self, path: &str) -> Option<&KeyEntry> {
        self.entries.iter().find(|e| e.path == path)
    }

    /// The key named `name` (the last path segment) whose value starts first at or after
    /// byte `offset`: where toml reports a key it was not asked for, at the key itself.
    pub fn named_after(&self, name: &str, offset: usize) -> Option<&KeyEntry> {
        self.entries
            .iter()
            .filter(|e| e.value.start >= offset)
            .filter(|e| e.path == name || e.path.ends_with(&format!(".{name}")))
            .min_by_key(|e| e.value.start)
    }

    /// The innermost key whose value's text covers byte `offset`.
    pub fn innermost_at(&self, offset: usize) -> Option<&KeyEntry> {
        self.entries
            .iter()
            .filter(|e| e.value.start <= offset && offset < e.value.end.max(e.value.start + 1))
            .min_by_key(|e| e.value.end - e.value.start)
    }
}

/// The shape of a TOML value, with spans on every key and value below it.
enum Node {
    Table(Vec<(String, Spanned<Node>)>),
    Array(Vec<Spanned<Node>>),
    Datetime,
    Leaf,
}

impl<'de> Deserialize<'de> for Node {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(NodeVisitor)
    }
}

/// The key under which toml's deserializer presents a datetime value.
const DATETIME_KEY: &str = "$__toml_private_datetime";

struct NodeVisitor;

impl<'de> Visitor<'de> for NodeVisitor {
    type Value = Node;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("any TOML value")
    }

    fn visit_bool<E>(self, _: bool) -> Result<Node, E> {
        Ok(Node::Leaf)
    }
    fn visit_i64<E>(self, _: i64) -> Result<Node, E> {
        Ok(Node::Leaf)
    }
    fn visit_u64<E>(self, _: u64) -> Result<Node, E> {
        Ok(Node::Leaf)
    }
    fn visit_f64<E>(self, _: f64) -> Result<Node, E> {
        Ok(Node::Leaf)
    }
    fn visit_str<E>(self, _: &str) -> Result<Node, E> {
        Ok(Node::Leaf)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Node, A::Error> {
        let mut items = Vec::new();
        while let Some(item) = seq.next_element::<Spanned<Node>>()? {
            items.push(item);
        }
        Ok(Node::Array(items))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Node, A::Error> {
        let mut children = Vec::new();
        while let Some(key) = map.next_key::<String>()? {
            if key == DATETIME_KEY {
                // toml hands a datetime over as a one-entry map; it is a leaf here.
                map.next_value::<IgnoredAny>()?;
                return Ok(Node::Datetime);
            }
            let value = map.next_value::<Spanned<Node>>()?;
            children.push((key, value));
        }
        Ok(Node::Table(children))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DOC: &str = "[image]\nwidth = 4\n\n[[sphere]]\nradius = 1.0\n\n[[sphere]]\ncenter = [1, 2, 3]\nradius = 2.0\n";

    #[test]
    fn finds_keys_of_arrays_of_tables_by_path() {
        let index = KeyIndex::parse(DOC).unwrap();
        let radius = index.get("sphere[1].radius").unwrap();
        assert_eq!(&DOC[radius.value.clone()], "2.0");
        assert_eq!(&DOC[index.get("image.width").unwrap().value.clone()], "4");
    }

    #[test]
    fn innermost_key_covers_an_offset() {
        let index = KeyIndex::parse(DOC).unwrap();
        let offset = DOC.find("2, 3]").unwrap();
        assert_eq!(
            index.innermost_at(offset).unwrap().path,
            "sphere[1].center[1]"
        );
        let offset = DOC.rfind("2.0").unwrap();
        assert_eq!(index.innermost_at(offset).unwrap().path, "sphere[1].radius");
    }

    #[test]
    fn datetimes_and_nested_values_do_not_break_the_index() {
        let doc = "when = 1979-05-27T07:32:00Z\n[a]\nb = { c = [[1], [2]] }\n";
        let index = KeyIndex::parse(doc).unwrap();
        assert!(index.get("a.b.c[1][0]").is_some());
        assert_eq!(index.get("when").unwrap().kind, "datetime");
        assert_eq!(index.get("a.b").unwrap().kind, "table");
    }
}
