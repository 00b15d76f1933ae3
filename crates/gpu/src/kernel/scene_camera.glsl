// ---------------------------------------------------------------------------------------
// Cameras (docs/physics.md, "Pixels and cameras"; scene::camera): the unit direction in the
// camera basis (forward, right, up) at image position (x, y) of the sample grid; false for
// a fisheye pixel outside its circle.

bool cameraDirection(vec2 p, out vec3 d) {
    d = vec3(0.0);
    float w = float(u_size.x), h = float(u_size.y);
    if (u_camera == 0) {
        vec2 halfFov = cis(radians(0.5 * u_fov.x));
        float t = halfFov.y / halfFov.x;
        float x = t * (2.0 * p.x / w - 1.0);
        float y = t * (h / w) * (1.0 - 2.0 * p.y / h);
        d = vec3(1.0, x, y) / sqrt(1.0 + x * x + y * y);
        return true;
    }
    if (u_camera == 1) {
        float alpha = radians(u_fov.x) * (p.x / w - 0.5);
        float beta = radians(u_fov.y) * (0.5 - p.y / h);
        d = vec3(cosA(beta) * cosA(alpha), cosA(beta) * sinA(alpha), sinA(beta));
        return true;
    }
    float dx = 2.0 * p.x / w - 1.0, dy = 1.0 - 2.0 * p.y / h;
    float rho = length(vec2(dx, dy));
    if (rho > 1.0) return false;
    float theta = rho * radians(0.5 * u_fov.x);
    vec2 sc = rho > 0.0 ? vec2(dx, dy) / rho : vec2(0.0, 1.0);
    d = vec3(cosA(theta), sinA(theta) * sc.x, sinA(theta) * sc.y);
    return true;
}

