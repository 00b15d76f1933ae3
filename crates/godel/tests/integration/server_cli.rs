//! Servers that no idle client can hold (issue 24): `godel view` under a low open-file limit
//! (`prlimit --nofile=128`) stays reachable with 400 half-open connections open, never uses
//! up its file descriptors, and closes the half-open ones; `godel view` and `godel explore`
//! end on SIGINT and SIGTERM while clients hold half-sent requests. (Before: 1100 half-open
//! connections, under the common limit of 1024 open files, made `godel view` unreachable and
//! none was closed after 40 s; the signals were ignored until the clients went away.)
//!
//! The read timeouts and waits here are deadlines against hanging forever, not speed checks:
//! the server's own bounds are 10 s for a request head and half a second to shut down.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use crate::common::{self, GODEL};

/// A deadline against hanging forever.
const DEADLINE: Duration = Duration::from_secs(60);

/// scenes/static-sphere.toml at 48×8, written into `dir`.
fn small_scene(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(testkit::scenes_dir().join("static-sphere.toml"))
        .unwrap()
        .replace("width = 720", "width = 48")
        .replace("height = 120", "height = 8");
    let scene = dir.join("s.toml");
    std::fs::write(&scene, text).unwrap();
    scene
}

/// The data file of [`small_scene`], rendered into `dir`.
fn small_data_file(dir: &Path) -> PathBuf {
    let o = common::render(&small_scene(dir), dir, &["-q"]);
    assert!(o.status.success(), "{o:?}");
    dir.join("static-sphere.exr")
}

/// A server started by `command` (its arguments ending in `--port 0`) and its port; killed
/// when dropped.
struct Server {
    child: Child,
    port: u16,
}

impl Server {
    fn start(command: &mut Command) -> Server {
        let mut child = command
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut line)
            .unwrap();
        let port = common::port_of(line.trim().rsplit(' ').next().unwrap());
        Server { child, port }
    }

    fn connect(&self) -> TcpStream {
        let stream = TcpStream::connect(("127.0.0.1", self.port)).unwrap();
        stream.set_read_timeout(Some(DEADLINE)).unwrap();
        stream
    }

    /// The file descriptors the server has open.
    fn open_files(&self) -> usize {
        std::fs::read_dir(format!("/proc/{}/fd", self.child.id()))
            .map(|d| d.count())
            .unwrap_or(0)
    }

    /// Sends `signal` and waits for the exit (at most [`DEADLINE`]); its exit code, or
    /// `None` if it did not end.
    fn signal(&mut self, signal: &str) -> Option<i32> {
        let sent = Command::new("kill")
            .args([signal, &self.child.id().to_string()])
            .status()
            .unwrap();
        assert!(sent.success());
        let started = Instant::now();
        while started.elapsed() < DEADLINE {
            if let Some(status) = self.child.try_wait().unwrap() {
                return status.code();
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        None
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A request for the file's description; the answer's status line.
fn info(server: &Server) -> String {
    let mut stream = server.connect();
    let port = server.port;
    let request =
        format!("GET /api/info HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\n\r\n");
    stream.write_all(request.as_bytes()).unwrap();
    let mut answer = String::new();
    stream
        .read_to_string(&mut answer)
        .expect("an answer before the deadline");
    answer.lines().next().unwrap_or_default().to_string()
}

/// A client that sent only the start of a request head.
fn half_open(server: &Server) -> TcpStream {
    let mut stream = server.connect();
    stream
        .write_all(b"GET /api/info HTTP/1.1\r\nHost: 127.0.0.1")
        .unwrap();
    stream
}

/// Whether the server closed `stream` (end of stream or reset) before the deadline.
fn closed(stream: &mut TcpStream) -> bool {
    let mut rest = Vec::new();
    match stream.read_to_end(&mut rest) {
        Ok(_) => true,
        Err(e) => e.kind() == std::io::ErrorKind::ConnectionReset,
    }
}

#[test]
fn half_open_clients_cannot_lock_others_out_under_a_low_open_file_limit() {
    let dir = tempfile::tempdir().unwrap();
    let exr = small_data_file(dir.path());
    let limit = 128;
    let server = Server::start(
        Command::new("prlimit")
            .arg(format!("--nofile={limit}"))
            .args([GODEL, "view", exr.to_str().unwrap(), "--port", "0"]),
    );
    let mut flood: Vec<TcpStream> = (0..400).map(|_| half_open(&server)).collect();
    // Everyone else is still served, while the flood is open.
    assert_eq!(info(&server), "HTTP/1.1 200 OK");
    let open = server.open_files();
    assert!(open < limit, "{open} files open under a limit of {limit}");
    // Every half-open connection is closed: the oldest to make room, the rest when their
    // head does not come.
    let still_open = flood.iter_mut().map(closed).filter(|c| !c).count();
    assert_eq!(still_open, 0);
    assert_eq!(info(&server), "HTTP/1.1 200 OK");
}

/// Clients that hold the server: a half-sent head, a half-sent body, a kept-alive connection.
fn holding_clients(server: &Server) -> Vec<TcpStream> {
    let port = server.port;
    let mut body = server.connect();
    let head = format!(
        "POST /api/png HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\
         Content-Type: application/json\r\nContent-Length: 1000\r\n\r\n{{\"shaders\""
    );
    body.write_all(head.as_bytes()).unwrap();
    let mut kept = server.connect();
    let request = format!("GET /api/info HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n");
    kept.write_all(request.as_bytes()).unwrap();
    let mut status = [0u8; 12];
    kept.read_exact(&mut status).unwrap();
    assert_eq!(&status, b"HTTP/1.1 200");
    vec![half_open(server), body, kept]
}

#[test]
fn view_and_explore_end_on_a_signal_whatever_their_clients_do() {
    let dir = tempfile::tempdir().unwrap();
    let exr = small_data_file(dir.path());
    let scene = small_scene(dir.path());
    for signal in ["-TERM", "-INT"] {
        for (command, file) in [("view", &exr), ("explore", &scene)] {
            let mut server = Server::start(Command::new(GODEL).args([
                command,
                file.to_str().unwrap(),
                "--port",
                "0",
            ]));
            let _clients = holding_clients(&server);
            // A moment for the server to read what they sent.
            std::thread::sleep(Duration::from_millis(200));
            let code = server.signal(signal);
            assert_eq!(code, Some(0), "godel {command} after kill {signal}");
        }
    }
}
