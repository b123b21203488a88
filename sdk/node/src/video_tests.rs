use std::io::{Read, Write};
use std::net::TcpStream;
use std::time::{Duration, Instant};

use jaus_as4::environment::video::StreamState;
use jaus_as4::environment::VideoHub;

use super::*;

fn server(max_viewers: usize, token: Option<&str>) -> (VideoHub, MjpegServer) {
    let file = VideoFile {
        listen: "127.0.0.1:0".parse().unwrap(),
        max_viewers,
        token: token.map(String::from),
        ..VideoFile::default()
    };
    let (hub, _) = file.hub();
    hub.add_stream(1);
    let s = MjpegServer::start(&file, hub.clone()).unwrap();
    (hub, s)
}

/// Sends `request`, reads the whole answer (the server closes).
fn get(s: &MjpegServer, request: &[u8]) -> Vec<u8> {
    let mut c = TcpStream::connect(s.local_addr()).unwrap();
    c.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    c.write_all(request).unwrap();
    let mut out = Vec::new();
    let _ = c.read_to_end(&mut out);
    out
}

fn status(answer: &[u8]) -> String {
    String::from_utf8_lossy(answer)
        .lines()
        .next()
        .unwrap_or_default()
        .to_string()
}

/// The JPEG parts of a multipart answer.
fn parts(answer: &[u8]) -> Vec<Vec<u8>> {
    let mut out = Vec::new();
    let mut rest = answer;
    let marker = b"Content-Type: image/jpeg\r\nContent-Length: ";
    while let Some(i) = rest.windows(marker.len()).position(|w| w == marker) {
        rest = &rest[i + marker.len()..];
        let end = rest.windows(4).position(|w| w == b"\r\n\r\n").unwrap();
        let n: usize = std::str::from_utf8(&rest[..end]).unwrap().parse().unwrap();
        out.push(rest[end + 4..end + 4 + n].to_vec());
        rest = &rest[end + 4 + n..];
    }
    out
}

#[test]
fn a_viewer_gets_the_frames_as_mjpeg_until_the_stream_stops() {
    let (hub, s) = server(2, None);
    hub.set_state(1, StreamState::Playing);
    let h = hub.clone();
    let publisher = std::thread::spawn(move || {
        // Each frame once the viewer is watching (so none is skipped).
        let t0 = Instant::now();
        while h.stats(1).unwrap().viewers == 0 && t0.elapsed() < Duration::from_secs(5) {
            std::thread::sleep(Duration::from_millis(5));
        }
        for i in 0..5u8 {
            h.publish(1, Instant::now(), vec![0xFF, 0xD8, i, 0xFF, 0xD9]);
            std::thread::sleep(Duration::from_millis(60));
        }
        h.set_state(1, StreamState::Stopped);
    });
    let answer = get(&s, b"GET /video/1 HTTP/1.1\r\nHost: 127.0.0.1:8090\r\n\r\n");
    publisher.join().unwrap();
    let text = String::from_utf8_lossy(&answer);
    assert_eq!(status(&answer), "HTTP/1.1 200 OK");
    assert!(text.contains("Content-Type: multipart/x-mixed-replace; boundary=jausframe"));
    assert!(text.ends_with("--jausframe--\r\n"), "{text}");
    let got = parts(&answer);
    assert_eq!(got.len(), 5, "{text}");
    for (i, p) in got.iter().enumerate() {
        assert_eq!(p, &[0xFF, 0xD8, i as u8, 0xFF, 0xD9]);
    }
    assert_eq!(s.stats().frames.load(Ordering::Relaxed), 5);
    // The viewer's place is free again.
    assert_eq!(hub.stats(1).unwrap().viewers, 0);
}

#[test]
fn what_is_not_a_viewer_of_a_playing_stream_is_refused_and_the_server_goes_on() {
    let (hub, s) = server(1, Some("s3cret"));
    // Stopped: 503, naming what plays it.
    let a = get(&s, b"GET /video/1?token=s3cret HTTP/1.1\r\n\r\n");
    assert_eq!(status(&a), "HTTP/1.1 503 Service Unavailable");
    assert!(String::from_utf8_lossy(&a).contains("Control Digital Video Sensor Stream"));
    hub.set_state(1, StreamState::Playing);
    let cases: [(&[u8], &str); 10] = [
        (
            b"GET /video/1?token=s3cret HTTP/1.1\r\nHost: evil.example:8090\r\n\r\n",
            "403",
        ),
        (b"POST /video/1?token=s3cret HTTP/1.1\r\n\r\n", "405"),
        (b"GET /video/1 HTTP/1.1\r\n\r\n", "403"),
        (b"GET /video/1?token=s3crex HTTP/1.1\r\n\r\n", "403"),
        (b"GET /video/9?token=s3cret HTTP/1.1\r\n\r\n", "404"),
        (b"GET /video/x?token=s3cret HTTP/1.1\r\n\r\n", "404"),
        (b"GET /../../etc/passwd HTTP/1.1\r\n\r\n", "404"),
        (b"GET /video/1 SPDY/3\r\n\r\n", "400"),
        (b"\xff\xfe\x00garbage\r\n\r\n", "400"),
        (b"GET /video/1?token=s3cret HTTP/1.1 extra\r\n\r\n", "400"),
    ];
    for (request, code) in cases {
        let a = get(&s, request);
        assert!(
            status(&a).starts_with(&format!("HTTP/1.1 {code} ")),
            "{request:?}: {}",
            status(&a)
        );
    }
    // A head that never ends is cut at 4096 bytes.
    let mut long = b"GET /video/1 HTTP/1.1\r\nX: ".to_vec();
    long.resize(MAX_REQUEST + 600, b'a');
    let mut c = TcpStream::connect(s.local_addr()).unwrap();
    c.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    let _ = c.write_all(&long);
    let mut a = Vec::new();
    let _ = c.read_to_end(&mut a);
    assert!(status(&a).starts_with("HTTP/1.1 431 "), "{}", status(&a));
    // One viewer at most: a second is refused while the first watches.
    let mut first = TcpStream::connect(s.local_addr()).unwrap();
    first
        .write_all(b"GET /video/1?token=s3cret HTTP/1.1\r\n\r\n")
        .unwrap();
    let t0 = Instant::now();
    while hub.stats(1).unwrap().viewers == 0 && t0.elapsed() < Duration::from_secs(5) {
        std::thread::sleep(Duration::from_millis(5));
    }
    let a = get(&s, b"GET /video/1?token=s3cret HTTP/1.1\r\n\r\n");
    assert_eq!(status(&a), "HTTP/1.1 503 Service Unavailable");
    assert_eq!(hub.stats(1).unwrap().viewers_refused, 1);
    drop(first);
    let st = s.stats();
    assert_eq!(st.bad_requests.load(Ordering::Relaxed), 5);
    assert_eq!(st.forbidden.load(Ordering::Relaxed), 3);
    assert_eq!(st.not_found.load(Ordering::Relaxed), 3);
    assert_eq!(st.unavailable.load(Ordering::Relaxed), 2);
    println!("{}", s.stats_line());
}

#[test]
fn connections_beyond_the_bound_are_closed_unanswered() {
    // One viewer: two connections at once are read, a third is closed.
    let (_hub, s) = server(1, None);
    let idle: Vec<TcpStream> = (0..2)
        .map(|_| TcpStream::connect(s.local_addr()).unwrap())
        .collect();
    let t0 = Instant::now();
    while s.stats().accepted.load(Ordering::Relaxed) < 2 && t0.elapsed() < Duration::from_secs(5) {
        std::thread::sleep(Duration::from_millis(5));
    }
    let a = get(&s, b"GET /video/1 HTTP/1.1\r\n\r\n");
    assert!(a.is_empty(), "{}", String::from_utf8_lossy(&a));
    assert_eq!(s.stats().busy.load(Ordering::Relaxed), 1);
    drop(idle);
}

#[test]
fn only_an_ip_or_localhost_may_be_the_host() {
    for (host, ok) in [
        ("127.0.0.1:8090", true),
        ("10.1.2.3", true),
        ("localhost:8090", true),
        ("LOCALHOST", true),
        ("[::1]:8090", true),
        ("evil.example", false),
        ("127.0.0.1.nip.io:8090", false),
        ("[evil]:80", false),
    ] {
        let head = format!("GET /video/1 HTTP/1.1\r\nHost: {host}\r\n\r\n");
        assert_eq!(host_allowed(&head), ok, "{host}");
    }
    assert!(
        host_allowed("GET /video/1 HTTP/1.0\r\n\r\n"),
        "no Host (HTTP/1.0)"
    );
}
