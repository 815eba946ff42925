//! # XML robot files: positions and numbers
//!
//! Shared by the CASPR and WireCenter readers: a parsed document that knows its file name, so
//! that every error names the file, the line and the element (and attribute) it is about.
//! Vectors in element text are numbers separated by any whitespace (CASPR writes
//! `<location>1.659 -2.850 3.221</location>`, some files use tabs or line breaks).
//!
//! ## References
//! - roxmltree: a read-only XML tree that keeps each node's byte range (hence its line).

use crate::RobotFileError;
use nalgebra::Vector3;
use roxmltree::{Document, Node};
use std::path::Path;

/// A parsed XML file with its name.
pub(crate) struct XmlFile<'a> {
    pub file: &'a Path,
    pub doc: Document<'a>,
}

impl<'a> XmlFile<'a> {
    /// Parses `text` (DTD declarations allowed: CASPR files name theirs; they are not fetched).
    pub fn parse(text: &'a str, file: &'a Path) -> Result<Self, RobotFileError> {
        let options = roxmltree::ParsingOptions {
            allow_dtd: true,
            nodes_limit: 1_000_000,
            ..Default::default()
        };
        let doc =
            Document::parse_with_options(text, options).map_err(|e| RobotFileError::Syntax {
                file: file.to_path_buf(),
                line: e.pos().row as usize,
                message: format!("not well-formed XML: {e}"),
            })?;
        Ok(Self { file, doc })
    }

    /// 1-based line of a node.
    pub fn line(&self, node: Node) -> usize {
        self.doc.text_pos_at(node.range().start).row as usize
    }

    /// An error about an element (and optionally one of its attributes).
    pub fn error(
        &self,
        node: Node,
        attribute: Option<&str>,
        message: impl Into<String>,
    ) -> RobotFileError {
        let line = match attribute.and_then(|a| node.attribute_node(a)) {
            Some(a) => self.doc.text_pos_at(a.range().start).row as usize,
            None => self.line(node),
        };
        RobotFileError::Element {
            file: self.file.to_path_buf(),
            line,
            element: node.tag_name().name().to_string(),
            attribute: attribute.map(str::to_string),
            message: message.into(),
        }
    }

    /// An element that cdpr does not model.
    pub fn unsupported(&self, node: Node, message: impl Into<String>) -> RobotFileError {
        RobotFileError::Unsupported {
            file: self.file.to_path_buf(),
            line: self.line(node),
            element: node.tag_name().name().to_string(),
            message: message.into(),
        }
    }

    /// The element children of `node`.
    pub fn elements<'b>(node: Node<'b, 'a>) -> impl Iterator<Item = Node<'b, 'a>> {
        node.children().filter(|n| n.is_element())
    }

    /// The only child element called `name` (error if absent or repeated).
    pub fn child<'b>(
        &self,
        node: Node<'b, 'a>,
        name: &str,
    ) -> Result<Node<'b, 'a>, RobotFileError> {
        let mut it = Self::elements(node).filter(|n| n.has_tag_name(name));
        let first = it
            .next()
            .ok_or_else(|| self.error(node, None, format!("missing child element <{name}>")))?;
        if let Some(second) = it.next() {
            return Err(self.error(second, None, format!("<{name}> given twice")));
        }
        Ok(first)
    }

    /// The child element called `name`, if present (error if repeated).
    pub fn optional_child<'b>(
        &self,
        node: Node<'b, 'a>,
        name: &str,
    ) -> Result<Option<Node<'b, 'a>>, RobotFileError> {
        if Self::elements(node).any(|n| n.has_tag_name(name)) {
            self.child(node, name).map(Some)
        } else {
            Ok(None)
        }
    }

    /// Finite numbers separated by whitespace in an element's text.
    pub fn numbers(&self, node: Node) -> Result<Vec<f64>, RobotFileError> {
        let text = node.text().unwrap_or("");
        text.split_whitespace()
            .map(|w| match w.parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                Ok(x) => Err(self.error(node, None, format!("{x} is not a finite number"))),
                Err(_) => Err(self.error(node, None, format!("`{w}` is not a number"))),
            })
            .collect()
    }

    /// One finite number in an element's text.
    pub fn number(&self, node: Node) -> Result<f64, RobotFileError> {
        match self.numbers(node)?.as_slice() {
            [x] => Ok(*x),
            v => Err(self.error(
                node,
                None,
                format!("expected one number, found {}", v.len()),
            )),
        }
    }

    /// A 3-vector in an element's text.
    pub fn vector3(&self, node: Node) -> Result<Vector3<f64>, RobotFileError> {
        match self.numbers(node)?.as_slice() {
            [x, y, z] => Ok(Vector3::new(*x, *y, *z)),
            v => Err(self.error(
                node,
                None,
                format!("expected 3 numbers (x y z), found {}", v.len()),
            )),
        }
    }

    /// A finite number in an attribute, if present.
    pub fn attr_number(&self, node: Node, name: &str) -> Result<Option<f64>, RobotFileError> {
        match node.attribute(name) {
            None => Ok(None),
            Some(v) => match v.trim().parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(Some(x)),
                Ok(x) => Err(self.error(node, Some(name), format!("{x} is not a finite number"))),
                Err(_) => Err(self.error(node, Some(name), format!("`{v}` is not a number"))),
            },
        }
    }

    /// A finite number in a required attribute.
    pub fn required_number(&self, node: Node, name: &str) -> Result<f64, RobotFileError> {
        self.attr_number(node, name)?
            .ok_or_else(|| self.error(node, Some(name), "missing"))
    }
}
