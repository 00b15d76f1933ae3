//! The rules the GPU kernel keeps so that no conforming driver can run it two ways
//! (docs/physics.md, "The GPU kernel"), checked on its text: stores into arrays, matrices and
//! vectors only at constant indices; no NaN test or NaN made; floats made ints only through
//! `toInt`; every variable set where it is declared, every out parameter first thing. Each
//! check is also shown to find the construct it forbids, in the form an earlier kernel had it.

use gpu::KERNEL;
use std::ops::Range;

const BUILTIN_TYPES: [&str; 16] = [
    "void", "float", "int", "uint", "bool", "vec2", "vec3", "vec4", "ivec2", "ivec3", "ivec4",
    "bvec2", "bvec3", "bvec4", "mat3", "mat4",
];
const ASSIGNMENTS: [&str; 9] = ["=", "+=", "-=", "*=", "/=", "++", "--", "&=", "|="];
/// What an index may hold besides constants and loop indices.
const ARITHMETIC: [&str; 7] = ["+", "-", "*", "/", "%", "(", ")"];

/// A GLSL source as tokens (identifiers, numbers, operators), comments and preprocessor lines
/// left out (so both sides of every `#if` are checked), and the names of its types.
struct Glsl {
    t: Vec<String>,
    types: Vec<String>,
}

fn is_word(s: &str) -> bool {
    s.chars().all(|c| c.is_alphanumeric() || c == '_')
}

/// An integer or float literal, or a name in capitals (a constant or a define).
fn is_constant(s: &str) -> bool {
    s.starts_with(|c: char| c.is_ascii_digit())
        || (s.starts_with(|c: char| c.is_ascii_uppercase())
            && s.chars()
                .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_'))
}

impl Glsl {
    fn new(source: &str) -> Glsl {
        let mut text = String::new();
        for line in source.lines() {
            let code = line.split("//").next().unwrap_or("");
            if !code.trim_start().starts_with('#') {
                text.push_str(code);
                text.push('\n');
            }
        }
        let c: Vec<char> = text.chars().collect();
        let mut t: Vec<String> = Vec::new();
        let mut i = 0;
        while i < c.len() {
            let start = i;
            if c[i].is_whitespace() {
                i += 1;
                continue;
            }
            if c[i].is_ascii_digit()
                || (c[i] == '.' && c.get(i + 1).is_some_and(char::is_ascii_digit))
            {
                // A number: digits, a point, an exponent with its sign, a suffix.
                while i < c.len()
                    && (c[i].is_ascii_alphanumeric()
                        || c[i] == '.'
                        || (matches!(c[i], '+' | '-') && matches!(c[i - 1], 'e' | 'E')))
                {
                    i += 1;
                }
            } else if c[i].is_alphanumeric() || c[i] == '_' {
                while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
                    i += 1;
                }
            } else {
                let two: String = c[i..(i + 2).min(c.len())].iter().collect();
                let double = ASSIGNMENTS.contains(&two.as_str())
                    || ["==", "!=", "<=", ">=", "&&", "||", "<<", ">>"].contains(&two.as_str());
                i += if double { 2 } else { 1 };
            }
            t.push(c[start..i].iter().collect());
        }
        let mut types: Vec<String> = BUILTIN_TYPES.iter().map(|s| s.to_string()).collect();
        for w in t.windows(2) {
            if w[0] == "struct" {
                types.push(w[1].clone());
            }
        }
        Glsl { t, types }
    }

    fn is_type(&self, s: &str) -> bool {
        self.types.iter().any(|t| t == s)
    }

    /// The index of the token that closes the bracket opened at `open`.
    fn closing(&self, open: usize) -> usize {
        let (o, c) = match self.t[open].as_str() {
            "(" => ("(", ")"),
            "[" => ("[", "]"),
            _ => ("{", "}"),
        };
        let mut depth = 0;
        for (i, s) in self.t.iter().enumerate().skip(open) {
            if s == o {
                depth += 1;
            } else if s == c {
                depth -= 1;
                if depth == 0 {
                    return i;
                }
            }
        }
        panic!("unbalanced {o} at token {open}");
    }

    /// The index of the token that opens the bracket closed at `close`.
    fn opening(&self, close: usize) -> usize {
        let mut depth = 0;
        for k in (0..=close).rev() {
            match self.t[k].as_str() {
                ")" | "]" | "}" => depth += 1,
                "(" | "[" | "{" => {
                    depth -= 1;
                    if depth == 0 {
                        return k;
                    }
                }
                _ => {}
            }
        }
        panic!("unbalanced bracket at token {close}");
    }

    /// One past the statement starting at `at`: a block, a loop, an if with its else, or a
    /// simple statement up to its semicolon.
    fn statement_end(&self, at: usize) -> usize {
        let t = &self.t;
        match t[at].as_str() {
            "{" => self.closing(at) + 1,
            "for" | "while" => self.statement_end(self.closing(at + 1) + 1),
            "if" => {
                let end = self.statement_end(self.closing(at + 1) + 1);
                if t.get(end).is_some_and(|s| s == "else") {
                    self.statement_end(end + 1)
                } else {
                    end
                }
            }
            _ => {
                let mut i = at;
                while t[i] != ";" {
                    i = if t[i] == "(" || t[i] == "[" {
                        self.closing(i) + 1
                    } else {
                        i + 1
                    };
                }
                i + 1
            }
        }
    }

    /// The function definitions: (name, parameter token ranges, body range without braces).
    fn functions(&self) -> Vec<(String, Vec<Range<usize>>, Range<usize>)> {
        let t = &self.t;
        let mut found = Vec::new();
        let mut i = 1;
        while i + 1 < t.len() {
            if self.is_type(&t[i - 1]) && is_word(&t[i]) && t[i + 1] == "(" {
                let close = self.closing(i + 1);
                if t.get(close + 1).is_some_and(|s| s == "{") {
                    let mut params = Vec::new();
                    let mut from = i + 2;
                    for (k, s) in t.iter().enumerate().take(close + 1).skip(i + 2) {
                        if s == "," || k == close {
                            params.push(from..k);
                            from = k + 1;
                        }
                    }
                    let end = self.closing(close + 1);
                    found.push((t[i].clone(), params, close + 2..end));
                    i = end;
                }
            }
            i += 1;
        }
        found
    }

    /// The loop variable of the `for` at `at` and the loop's body, if the loop is one that
    /// compilers unroll into constant indices: its index runs between constant bounds, and its
    /// body leaves the index alone, has no loop and calls none of the kernel's functions
    /// (softpipe stored at wrong indices in a loop over a frame's columns that called them).
    fn constant_loop(&self, at: usize) -> Option<(String, Range<usize>)> {
        let t = &self.t;
        let close = self.closing(at + 1);
        let parts: Vec<&[String]> = t[at + 2..close].split(|s| s == ";").collect();
        let [init, cond, step] = parts.as_slice() else {
            return None;
        };
        let name = init.get(1)?.clone();
        let constant = |e: &[String]| {
            e.iter()
                .all(|s| is_constant(s) || ARITHMETIC.contains(&s.as_str()))
        };
        let bounded = init.len() > 3
            && init[0] == "int"
            && init[2] == "="
            && constant(&init[3..])
            && cond.len() > 2
            && cond[0] == name
            && (cond[1] == "<" || cond[1] == "<=")
            && constant(&cond[2..])
            && step.len() == 2
            && step[0] == name
            && step[1] == "++";
        let body = close + 1..self.statement_end(close + 1);
        let changed = t[body.clone()].windows(2).any(|w| {
            (w[0] == name && ASSIGNMENTS.contains(&w[1].as_str()))
                || (w[1] == name && ["++", "--"].contains(&w[0].as_str()))
        });
        let functions: Vec<String> = self.functions().into_iter().map(|(f, _, _)| f).collect();
        let heavy = t[body.clone()].windows(2).any(|w| {
            ["for", "while"].contains(&w[0].as_str()) || (w[1] == "(" && functions.contains(&w[0]))
        });
        (bounded && !changed && !heavy).then_some((name, body))
    }

    /// Whether the element expression t[start..end] is stored into: assigned, incremented,
    /// or passed as an out argument (`outs`: function name and out parameter positions).
    fn stored(&self, start: usize, end: usize, outs: &[(String, Vec<usize>)]) -> bool {
        let t = &self.t;
        if t.get(end)
            .is_some_and(|s| ASSIGNMENTS.contains(&s.as_str()))
            || (start > 0 && ["++", "--"].contains(&t[start - 1].as_str()))
        {
            return true;
        }
        // The call around the expression, and its argument position there.
        let (mut k, mut position) = (start, 0);
        while k > 0 {
            k -= 1;
            match t[k].as_str() {
                ")" | "]" => k = self.opening(k),
                "," => position += 1,
                "(" => {
                    let f = &t[k - 1];
                    return outs
                        .iter()
                        .any(|(name, p)| name == f && p.contains(&position));
                }
                _ if !ASSIGNMENTS.contains(&t[k].as_str())
                    && ![";", "{", "}", "?", ":", "return"].contains(&t[k].as_str()) => {}
                _ => return false,
            }
        }
        false
    }

    /// Every store into an element whose index is not made of constants and the indices of
    /// the constant loops around it, as "index in `element`".
    fn runtime_stores(&self) -> Vec<String> {
        let t = &self.t;
        let outs: Vec<(String, Vec<usize>)> = self
            .functions()
            .into_iter()
            .map(|(name, params, _)| {
                let p = (params.iter().enumerate())
                    .filter(|(_, r)| ["out", "inout"].contains(&t[r.start].as_str()))
                    .map(|(k, _)| k)
                    .collect();
                (name, p)
            })
            .collect();
        let loops: Vec<(String, Range<usize>)> = (0..t.len())
            .filter(|&i| t[i] == "for")
            .filter_map(|i| self.constant_loop(i))
            .collect();
        let mut bad = Vec::new();
        for i in 1..t.len() {
            // An element: a name or an element, then `[`; not a declaration (`float a[N]`) or
            // an array type (`vec4[2](…)`).
            let element =
                t[i] == "[" && (is_word(&t[i - 1]) || t[i - 1] == "]") && !self.is_type(&t[i - 1]);
            if !element || (i >= 2 && self.is_type(&t[i - 2])) {
                continue;
            }
            let mut start = i - 1;
            while t[start] == "]" {
                start = self.opening(start) - 1;
            }
            let close = self.closing(i);
            let mut end = close + 1;
            while end < t.len() && (t[end] == "[" || t[end] == ".") {
                end = if t[end] == "[" {
                    self.closing(end) + 1
                } else {
                    end + 2
                };
            }
            if !self.stored(start, end, &outs) {
                continue;
            }
            let live: Vec<&str> = (loops.iter())
                .filter(|(_, body)| body.contains(&i))
                .map(|(name, _)| name.as_str())
                .collect();
            let index = &t[i + 1..close];
            let constant = index.iter().all(|s| {
                is_constant(s) || live.contains(&s.as_str()) || ARITHMETIC.contains(&s.as_str())
            });
            if !constant {
                bad.push(format!(
                    "{} in `{}`",
                    index.join(" "),
                    t[start..end].join(" ")
                ));
            }
        }
        bad
    }

    /// Names the kernel must not use: NaN tests (which a compiler that assumes no NaN may
    /// fold away) and bit casts to float (which make NaN and infinity).
    /// The conditional expressions (`c ? a : b`) whose branch is a structure's constructor or
    /// a call of a function returning one, after the `?` or the `:` (variables are not told
    /// apart: the kernel's names are not scoped here). WebGL (ANGLE) refuses them, where
    /// GLSL ES 3.00 allows them.
    fn struct_conditionals(&self) -> Vec<String> {
        let t = &self.t;
        let structs: Vec<&String> = (self.types.iter())
            .filter(|s| !BUILTIN_TYPES.contains(&s.as_str()))
            .collect();
        let mut valued: Vec<&str> = structs.iter().map(|s| s.as_str()).collect();
        for i in 1..t.len().saturating_sub(1) {
            if structs.contains(&&t[i - 1]) && is_word(&t[i]) && t[i + 1] == "(" {
                valued.push(&t[i]); // a function returning a structure
            }
        }
        let mut bad = Vec::new();
        for i in 0..t.len().saturating_sub(2) {
            let call = t[i + 2] == "(";
            if (t[i] == "?" || t[i] == ":") && valued.contains(&t[i + 1].as_str()) && call {
                bad.push(format!("{} {}", t[i], t[i + 1]));
            }
        }
        bad
    }

    fn nan_words(&self) -> Vec<String> {
        let forbidden = ["isnan", "isinf", "intBitsToFloat", "uintBitsToFloat"];
        self.t
            .iter()
            .filter(|s| forbidden.contains(&s.as_str()))
            .cloned()
            .collect()
    }

    /// The names declared with a float type (variables, parameters, uniforms, fields).
    fn float_names(&self) -> Vec<String> {
        let t = &self.t;
        let float = ["float", "vec2", "vec3", "vec4", "mat3", "mat4"];
        let mut names = Vec::new();
        for i in 0..t.len().saturating_sub(1) {
            if !float.contains(&t[i].as_str()) || !is_word(&t[i + 1]) {
                continue;
            }
            names.push(t[i + 1].clone());
            // Further declarators of the statement: `float a = 0.0, b = 1.0;`.
            let mut k = i + 2;
            while k < t.len() && ![";", ")", "{"].contains(&t[k].as_str()) {
                if t[k] == "(" || t[k] == "[" {
                    k = self.closing(k);
                } else if t[k] == "," && is_word(&t[k + 1]) {
                    names.push(t[k + 1].clone());
                }
                k += 1;
            }
        }
        names
    }

    /// Conversions to int other than toInt's own (a finite float clamped to the int range
    /// first) and of the fragment's coordinates (below the render target's size): `int(…)`,
    /// `uint(…)` or `ivecN(…)` of anything but integer names, literals and operators.
    fn int_conversions(&self) -> Vec<String> {
        let t = &self.t;
        let floats = self.float_names();
        let to_int = (self.functions().into_iter())
            .find(|(name, _, _)| name == "toInt")
            .map(|(_, _, body)| body);
        let mut bad = Vec::new();
        for i in 1..t.len().saturating_sub(1) {
            let conversion = ["int", "uint", "ivec2", "ivec3", "ivec4"].contains(&t[i].as_str())
                && t[i + 1] == "(";
            if !conversion
                || self.is_type(&t[i - 1])
                || to_int.as_ref().is_some_and(|b| b.contains(&i))
            {
                continue;
            }
            let args = &t[i + 2..self.closing(i + 1)];
            let integers = args.iter().enumerate().all(|(k, s)| {
                let call = args.get(k + 1).is_some_and(|n| n == "(");
                (is_word(s)
                    && !s.starts_with(|c: char| c.is_ascii_digit())
                    && !floats.contains(s)
                    && !call)
                    || s.chars().all(|c| c.is_ascii_digit())
                    || ["+", "-", "*", "/", "%", "(", ")", ",", "&", "|"].contains(&s.as_str())
            });
            if !(integers || args.join("") == "gl_FragCoord.xy") {
                bad.push(format!("{}({})", t[i], args.join(" ")));
            }
        }
        bad
    }

    /// Variables declared without a value (as "name"), except global arrays that a constant
    /// loop over their whole size writes at its index; and out parameters not set by the
    /// function's first statements (as "function: name").
    fn unset(&self) -> Vec<String> {
        let t = &self.t;
        let mut bad = Vec::new();
        let functions = self.functions();
        let loops: Vec<(String, Range<usize>, String)> = (0..t.len())
            .filter(|&i| t[i] == "for")
            .filter_map(|i| {
                let (name, body) = self.constant_loop(i)?;
                let close = self.closing(i + 1);
                let cond = t[i + 2..close].split(|s| s == ";").nth(1)?;
                (cond[1] == "<" && t[i + 5] == "0").then(|| (name, body, cond[2..].join(" ")))
            })
            .collect();
        let mut depth = 0;
        let mut i = 0;
        while i + 1 < t.len() {
            let s = t[i].as_str();
            if s == "struct" {
                i = self.closing(i + 2) + 1;
                continue;
            }
            if s == "{" {
                depth += 1;
            } else if s == "}" {
                depth -= 1;
            }
            let statement_start = i == 0 || [";", "{", "}"].contains(&t[i - 1].as_str());
            let declaration = statement_start
                && self.is_type(s)
                && s != "void"
                && is_word(&t[i + 1])
                && t[i + 2] != "(";
            if !declaration {
                i += 1;
                continue;
            }
            // Each declarator: a name, maybe a size, maybe a value.
            let mut k = i + 1;
            loop {
                let name = t[k].clone();
                let mut size = None;
                k += 1;
                if t[k] == "[" {
                    size = Some(t[k + 1..self.closing(k)].join(" "));
                    k = self.closing(k) + 1;
                }
                if t[k] == "=" {
                    while ![",", ";"].contains(&t[k].as_str()) {
                        k = if t[k] == "(" || t[k] == "[" {
                            self.closing(k) + 1
                        } else {
                            k + 1
                        };
                    }
                } else {
                    let filled = depth == 0
                        && size.as_ref().is_some_and(|size| {
                            loops.iter().any(|(v, body, bound)| {
                                bound == size
                                    && t[body.clone()].windows(5).any(|w| {
                                        w[0] == name
                                            && w[1] == "["
                                            && w[2] == *v
                                            && w[3] == "]"
                                            && w[4] == "="
                                    })
                            })
                        });
                    if !filled {
                        bad.push(name);
                    }
                }
                if t[k] == ";" {
                    break;
                }
                k += 1;
            }
            i = k + 1;
        }
        for (name, params, body) in functions {
            let outs: Vec<&String> = (params.iter())
                .filter(|r| ["out", "inout"].contains(&t[r.start].as_str()))
                .map(|r| &t[r.end - 1])
                .collect();
            let mut k = body.start;
            let mut set = Vec::new();
            while is_word(&t[k]) && t[k + 1] == "=" {
                set.push(&t[k]);
                k = self.statement_end(k);
            }
            for p in outs {
                if !set.contains(&p) {
                    bad.push(format!("{name}: {p}"));
                }
            }
        }
        bad
    }
}

#[test]
fn the_kernel_stores_only_at_constant_indices() {
    let bad = Glsl::new(KERNEL).runtime_stores();
    assert!(bad.is_empty(), "stores at a runtime index: {bad:#?}");
}

#[test]
fn stores_at_runtime_indices_are_found() {
    // The forms an earlier kernel had: the probe double buffer, a light's channel, an out
    // argument, a field; and what is allowed.
    let old = "void f(vec4 e, out mat4 m) { m = mat4(0.0); }\n\
               void g(int i) { probeBuf[N_OBJECTS - eStart + eObj] = qAnswer; }\n\
               void h(int li, float v) { slots[5 + li / 4][li % 4] = v; }\n\
               void k(int i) { f(e, oDX[i]); fbLast[i] += 1.0; ++count[i]; p[i].f = 0.0; }\n\
               void ok(int i) { float a[4]; vec4 b[2] = vec4[2](vec4(0.0), vec4(1.0));\n\
                 for (int j = 0; j < N_OBJECTS; j++) { if (j == i) a[j] = b[i].x; }\n\
                 b[1].x = a[i]; f(a[i], m); }\n\
               void runtimeBound(int n) { for (int j = 0; j < n; j++) a[j] = 1.0; }\n\
               void heavy() { for (int c = 0; c < 4; c++) m[c] = f(e, m); }\n";
    assert_eq!(
        Glsl::new(old).runtime_stores(),
        [
            "N_OBJECTS - eStart + eObj in `probeBuf [ N_OBJECTS - eStart + eObj ]`",
            "5 + li / 4 in `slots [ 5 + li / 4 ] [ li % 4 ]`",
            "li % 4 in `slots [ 5 + li / 4 ] [ li % 4 ]`",
            "i in `oDX [ i ]`",
            "i in `fbLast [ i ]`",
            "i in `count [ i ]`",
            "i in `p [ i ] . f`",
            "j in `a [ j ]`",
            "c in `m [ c ]`",
        ]
    );
}

#[test]
fn the_kernel_has_no_conditional_of_structures() {
    let bad = Glsl::new(KERNEL).struct_conditionals();
    assert!(
        bad.is_empty(),
        "?: of structures (WebGL refuses them): {bad:?}"
    );
    // The forms the kernel had: a function's result and a constructor.
    let old = "struct P { int a; };\nP f(int i) { return P(i); }\n\
               void g(bool b) { P p = b ? f(1) : f(2); P q = b ? p : P(0); float x = b ? 1.0 : 2.0; }\n";
    assert_eq!(Glsl::new(old).struct_conditionals(), ["? f", ": f", ": P"]);
}

#[test]
fn the_kernel_tests_no_nan_and_makes_none() {
    let words = Glsl::new(KERNEL).nan_words();
    assert!(words.is_empty(), "{words:?}");
    // The kernel's finiteness test before: a compiler that assumes no NaN may fold isnan.
    assert_eq!(
        Glsl::new("bool finite(float v) { return !isnan(v) && abs(v) < 1e38; }").nan_words(),
        ["isnan"]
    );
}

#[test]
fn the_kernel_makes_floats_ints_only_through_to_int() {
    let bad = Glsl::new(KERNEL).int_conversions();
    assert!(bad.is_empty(), "conversions: {bad:#?}");
    let old = "int toInt(float v, int lo, int hi) { return int(clamp(v, float(lo), float(hi))); }\n\
               void f(float j, int i) { int q = int(j * 0.5) & 3; int n = int(clamp(ceil(j), 1.0, 1e5));\n\
               ivec2 p = ivec2(gl_FragCoord.xy); ivec2 c = ivec2(i % W, i / W); int k = toInt(j, 0, 3); }";
    assert_eq!(
        Glsl::new(old).int_conversions(),
        ["int(j * 0.5)", "int(clamp ( ceil ( j ) , 1.0 , 1e5 ))"]
    );
}

#[test]
fn the_kernel_sets_every_variable_before_reading_it() {
    let bad = Glsl::new(KERNEL).unset();
    assert!(bad.is_empty(), "declared without a value: {bad:#?}");
    let old = "struct P { float f; };\n\
               float a[N]; float b[N]; P p; float x = 1.0, y;\n\
               void clear() { for (int i = 0; i < N; i++) { a[i] = 0.0; } }\n\
               bool box(int i, out vec3 lo, out vec3 hi) { if (i < 0) return false; lo = vec3(0.0); hi = lo; return true; }\n\
               void push(out vec4 e, out vec4 k) { e = vec4(0.0); k = e; vec4 o; }";
    assert_eq!(
        Glsl::new(old).unset(),
        ["b", "p", "y", "o", "box: lo", "box: hi"]
    );
}
