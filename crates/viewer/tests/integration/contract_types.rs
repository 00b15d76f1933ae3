//! The page's JSON contract (crates/viewer/page/contract.d.ts) read as types, and JSON values
//! checked against them, for the contract tests (`contract.rs`). The file is written in a
//! small part of TypeScript, which this reads and nothing more: `export interface NAME {`
//! with one `field: TYPE;` or `field?: TYPE;` a line, `export type NAME = TYPE;`, and the
//! types number, string, boolean, null, 'literals', true, false, NAME, T[], [tuples],
//! (parentheses), unions and Record<string, T>; comments are skipped.
//!
//! A value is of an interface when it is an object with every field that is not optional,
//! each of its type, and no other field. The fields of every value that passed are noted, so
//! that a test can ask which declared fields no answer or body ever had.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::Mutex;

use serde_json::Value;

/// A type of the contract.
#[derive(Clone, Debug, PartialEq)]
pub enum Type {
    Number,
    String,
    Boolean,
    Null,
    /// A string, `true` or `false` as a type.
    Literal(Value),
    /// An interface or alias declared in the file.
    Named(String),
    Array(Box<Type>),
    Tuple(Vec<Type>),
    Union(Vec<Type>),
    /// `Record<string, T>`: an object of any keys.
    Record(Box<Type>),
}

/// A field of an interface.
#[derive(Clone, Debug, PartialEq)]
pub struct Field {
    pub name: String,
    pub optional: bool,
    pub ty: Type,
}

/// A declaration: an interface's fields, or an alias.
#[derive(Clone, Debug, PartialEq)]
pub enum Decl {
    Interface(Vec<Field>),
    Alias(Type),
}

/// The declarations of a contract file, and the (interface, field) pairs seen so far in
/// values that passed [`Contract::check`].
pub struct Contract {
    pub decls: BTreeMap<String, Decl>,
    seen: Mutex<BTreeSet<(String, String)>>,
}

/// The page's contract, read from crates/viewer/page/contract.d.ts.
pub fn page_contract() -> Contract {
    Contract::parse(include_str!("../../page/contract.d.ts")).expect("contract.d.ts reads")
}

#[derive(Clone, Debug, PartialEq)]
enum Token {
    Word(String),
    Str(String),
    Punct(char),
}

fn tokens(text: &str) -> Result<Vec<Token>, String> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c.is_whitespace() {
            i += 1;
        } else if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let end = (i + 2..chars.len().saturating_sub(1))
                .find(|&k| chars[k] == '*' && chars[k + 1] == '/')
                .ok_or("a comment is not closed")?;
            i = end + 2;
        } else if c == '\'' {
            let end = (i + 1..chars.len())
                .find(|&k| chars[k] == '\'')
                .ok_or("a string is not closed")?;
            out.push(Token::Str(chars[i + 1..end].iter().collect()));
            i = end + 1;
        } else if c.is_alphanumeric() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            out.push(Token::Word(chars[start..i].iter().collect()));
        } else if "{};:?|[](),<>=".contains(c) {
            out.push(Token::Punct(c));
            i += 1;
        } else {
            return Err(format!("unexpected character {c:?}"));
        }
    }
    Ok(out)
}

/// A reader over the tokens.
struct Reader {
    tokens: Vec<Token>,
    at: usize,
}

impl Reader {
    fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.at)
    }

    fn next(&mut self) -> Result<Token, String> {
        let t = self.peek().cloned().ok_or("the file ends too soon")?;
        self.at += 1;
        Ok(t)
    }

    fn punct(&mut self, c: char) -> Result<(), String> {
        match self.next()? {
            Token::Punct(p) if p == c => Ok(()),
            t => Err(format!("expected {c:?}, found {t:?}")),
        }
    }

    fn eat(&mut self, c: char) -> bool {
        if self.peek() == Some(&Token::Punct(c)) {
            self.at += 1;
            true
        } else {
            false
        }
    }

    fn word(&mut self) -> Result<String, String> {
        match self.next()? {
            Token::Word(w) => Ok(w),
            t => Err(format!("expected a name, found {t:?}")),
        }
    }

    /// `A | B | …`, a leading `|` allowed.
    fn ty(&mut self) -> Result<Type, String> {
        self.eat('|');
        let mut branches = vec![self.postfix()?];
        while self.eat('|') {
            branches.push(self.postfix()?);
        }
        Ok(if branches.len() == 1 {
            branches.remove(0)
        } else {
            Type::Union(branches)
        })
    }

    /// A primary type followed by any number of `[]`.
    fn postfix(&mut self) -> Result<Type, String> {
        let mut t = self.primary()?;
        while self.peek() == Some(&Token::Punct('['))
            && self.tokens.get(self.at + 1) == Some(&Token::Punct(']'))
        {
            self.at += 2;
            t = Type::Array(Box::new(t));
        }
        Ok(t)
    }

    fn primary(&mut self) -> Result<Type, String> {
        Ok(match self.next()? {
            Token::Str(s) => Type::Literal(Value::String(s)),
            Token::Punct('(') => {
                let t = self.ty()?;
                self.punct(')')?;
                t
            }
            Token::Punct('[') => {
                let mut items = vec![self.ty()?];
                while self.eat(',') {
                    items.push(self.ty()?);
                }
                self.punct(']')?;
                Type::Tuple(items)
            }
            Token::Word(w) => match w.as_str() {
                "number" => Type::Number,
                "string" => Type::String,
                "boolean" => Type::Boolean,
                "null" => Type::Null,
                "true" => Type::Literal(Value::Bool(true)),
                "false" => Type::Literal(Value::Bool(false)),
                "Record" => {
                    self.punct('<')?;
                    let key = self.word()?;
                    if key != "string" {
                        return Err(format!("Record<{key}, …>: only string keys"));
                    }
                    self.punct(',')?;
                    let t = self.ty()?;
                    self.punct('>')?;
                    Type::Record(Box::new(t))
                }
                _ => Type::Named(w),
            },
            t => return Err(format!("expected a type, found {t:?}")),
        })
    }

    fn interface(&mut self) -> Result<Vec<Field>, String> {
        self.punct('{')?;
        let mut fields = Vec::new();
        while !self.eat('}') {
            let name = self.word()?;
            let optional = self.eat('?');
            self.punct(':')?;
            let ty = self.ty()?;
            self.punct(';')?;
            fields.push(Field { name, optional, ty });
        }
        Ok(fields)
    }
}

impl Contract {
    /// Reads a contract file; an error says where it went wrong.
    pub fn parse(text: &str) -> Result<Contract, String> {
        let mut r = Reader {
            tokens: tokens(text)?,
            at: 0,
        };
        let mut decls = BTreeMap::new();
        while r.peek().is_some() {
            let export = r.word()?;
            if export != "export" {
                return Err(format!("expected `export`, found {export:?}"));
            }
            let kind = r.word()?;
            let name = r.word()?;
            let decl = match kind.as_str() {
                "interface" => Decl::Interface(r.interface()?),
                "type" => {
                    r.punct('=')?;
                    let t = r.ty()?;
                    r.punct(';')?;
                    Decl::Alias(t)
                }
                _ => {
                    return Err(format!(
                        "{name}: expected interface or type, found {kind:?}"
                    ))
                }
            };
            if decls.insert(name.clone(), decl).is_some() {
                return Err(format!("{name} is declared twice"));
            }
        }
        Ok(Contract {
            decls,
            seen: Mutex::new(BTreeSet::new()),
        })
    }

    /// Whether `value` is of the declared type `name`; an error gives the path to the first
    /// field that is not (`Info.defaults.time.mode: …`). The fields of a value that passes are
    /// noted as seen.
    pub fn check(&self, name: &str, value: &Value) -> Result<(), String> {
        let mut seen = Vec::new();
        self.value(&Type::Named(name.to_string()), value, name, &mut seen)?;
        self.seen.lock().unwrap().extend(seen);
        Ok(())
    }

    /// The names used as types but declared nowhere.
    pub fn undeclared(&self) -> BTreeSet<String> {
        fn names(t: &Type, out: &mut BTreeSet<String>) {
            match t {
                Type::Named(n) => {
                    out.insert(n.clone());
                }
                Type::Array(t) | Type::Record(t) => names(t, out),
                Type::Tuple(ts) | Type::Union(ts) => ts.iter().for_each(|t| names(t, out)),
                _ => {}
            }
        }
        let mut used = BTreeSet::new();
        for decl in self.decls.values() {
            match decl {
                Decl::Interface(fields) => fields.iter().for_each(|f| names(&f.ty, &mut used)),
                Decl::Alias(t) => names(t, &mut used),
            }
        }
        used.retain(|n| !self.decls.contains_key(n));
        used
    }

    /// The declared fields (`Interface.field`) no value that passed has had so far.
    pub fn unseen(&self) -> Vec<String> {
        let seen = self.seen.lock().unwrap();
        let mut out = Vec::new();
        for (name, decl) in &self.decls {
            if let Decl::Interface(fields) = decl {
                for f in fields {
                    if !seen.contains(&(name.clone(), f.name.clone())) {
                        out.push(format!("{name}.{}", f.name));
                    }
                }
            }
        }
        out
    }

    fn value(
        &self,
        t: &Type,
        v: &Value,
        path: &str,
        seen: &mut Vec<(String, String)>,
    ) -> Result<(), String> {
        let wrong = |what: &str| Err(format!("{path}: {v} is not {what}"));
        match t {
            Type::Number if v.is_number() => Ok(()),
            Type::Number => wrong("a number"),
            Type::String if v.is_string() => Ok(()),
            Type::String => wrong("a string"),
            Type::Boolean if v.is_boolean() => Ok(()),
            Type::Boolean => wrong("a boolean"),
            Type::Null if v.is_null() => Ok(()),
            Type::Null => wrong("null"),
            Type::Literal(l) if v == l => Ok(()),
            Type::Literal(l) => wrong(&l.to_string()),
            Type::Array(item) => match v.as_array() {
                Some(items) => (items.iter().enumerate())
                    .try_for_each(|(i, x)| self.value(item, x, &format!("{path}[{i}]"), seen)),
                None => wrong("an array"),
            },
            Type::Tuple(types) => match v.as_array() {
                Some(items) if items.len() == types.len() => (types.iter().zip(items).enumerate())
                    .try_for_each(|(i, (t, x))| self.value(t, x, &format!("{path}[{i}]"), seen)),
                _ => wrong(&format!("an array of {}", types.len())),
            },
            Type::Record(item) => match v.as_object() {
                Some(map) => (map.iter())
                    .try_for_each(|(k, x)| self.value(item, x, &format!("{path}.{k}"), seen)),
                None => wrong("an object"),
            },
            Type::Union(branches) => {
                let mut why = Vec::new();
                for b in branches {
                    // A branch that fails notes nothing as seen.
                    let mut mine = Vec::new();
                    match self.value(b, v, path, &mut mine) {
                        Ok(()) => {
                            seen.extend(mine);
                            return Ok(());
                        }
                        Err(e) => why.push(e),
                    }
                }
                Err(format!(
                    "{path}: of no branch of the union ({})",
                    why.join("; ")
                ))
            }
            Type::Named(name) => match self.decls.get(name) {
                None => Err(format!("{path}: the type {name} is not declared")),
                Some(Decl::Alias(t)) => self.value(t, v, path, seen),
                Some(Decl::Interface(fields)) => {
                    let Some(map) = v.as_object() else {
                        return wrong(&format!("an object ({name})"));
                    };
                    for f in fields {
                        match map.get(&f.name) {
                            Some(x) => {
                                self.value(&f.ty, x, &format!("{path}.{}", f.name), seen)?;
                                seen.push((name.clone(), f.name.clone()));
                            }
                            None if f.optional => {}
                            None => return Err(format!("{path}: no field {} ({name})", f.name)),
                        }
                    }
                    match map.keys().find(|k| !fields.iter().any(|f| &f.name == *k)) {
                        Some(k) => Err(format!("{path}: {name} declares no field {k}")),
                        None => Ok(()),
                    }
                }
            },
        }
    }
}
