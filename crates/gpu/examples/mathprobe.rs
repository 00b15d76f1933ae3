use glow::HasContext;
fn main() {
    let ctx = gpu::context::Context::new().unwrap();
    let gl = &ctx.gl;
    let n = 4096usize;
    let frag = r#"#version 300 es
precision highp float;
out vec4 o;
void main() {
    float t = (gl_FragCoord.x - 0.5) / 4096.0;
    float x = -1.0 + 2.0 * t;
    o = vec4(exp(x * 3.0), log(x + 1.5), atan(x * 10.0), cos(x * 3.0));
}"#;
    let vert = "#version 300 es\nvoid main(){ vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)); gl_Position = vec4(p*2.0-1.0,0.0,1.0);}";
    unsafe {
        let prog = gl.create_program().unwrap();
        for (k, s) in [(glow::VERTEX_SHADER, vert), (glow::FRAGMENT_SHADER, frag)] {
            let sh = gl.create_shader(k).unwrap();
            gl.shader_source(sh, s);
            gl.compile_shader(sh);
            assert!(
                gl.get_shader_compile_status(sh),
                "{}",
                gl.get_shader_info_log(sh)
            );
            gl.attach_shader(prog, sh);
        }
        gl.link_program(prog);
        gl.use_program(Some(prog));
        let tex = gl.create_texture().unwrap();
        gl.bind_texture(glow::TEXTURE_2D, Some(tex));
        gl.tex_storage_2d(glow::TEXTURE_2D, 1, glow::RGBA32F, n as i32, 1);
        let fb = gl.create_framebuffer().unwrap();
        gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fb));
        gl.framebuffer_texture_2d(
            glow::FRAMEBUFFER,
            glow::COLOR_ATTACHMENT0,
            glow::TEXTURE_2D,
            Some(tex),
            0,
        );
        let vao = gl.create_vertex_array().unwrap();
        gl.bind_vertex_array(Some(vao));
        gl.viewport(0, 0, n as i32, 1);
        gl.draw_arrays(glow::TRIANGLES, 0, 3);
        let mut data = vec![0f32; n * 4];
        gl.read_pixels(
            0,
            0,
            n as i32,
            1,
            glow::RGBA,
            glow::FLOAT,
            glow::PixelPackData::Slice(Some(std::slice::from_raw_parts_mut(
                data.as_mut_ptr().cast(),
                n * 16,
            ))),
        );
        let mut worst = [0f64; 4];
        for i in 0..n {
            let x = -1.0 + 2.0 * ((i as f32 + 0.5 - 0.5) / 4096.0) as f64;
            let x = x as f32 as f64;
            let exact = [
                (x * 3.0).exp(),
                (x + 1.5).ln(),
                (x * 10.0).atan(),
                (x * 3.0).cos(),
            ];
            for k in 0..4 {
                worst[k] = worst[k].max((data[4 * i + k] as f64 - exact[k]).abs());
            }
        }
        println!(
            "{}: exp {:e} log {:e} atan {:e} cos {:e}",
            ctx.renderer, worst[0], worst[1], worst[2], worst[3]
        );
    }
}
