// The scene pass: flat-shaded triangles in the observer's frame, coloured
// by their base colour's hue shifted by the Doppler factor (luminance
// kept) and scaled by the searchlight intensity. Positions arrive relative to the eye.

struct Camera {
    view_proj: mat4x4<f32>,
    light: vec4<f32>,
};

@group(0) @binding(0) var<uniform> camera: Camera;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) colour: vec3<f32>,
    @location(2) doppler: f32,
    @location(3) intensity: f32,
};

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) position: vec3<f32>,
    @location(1) colour: vec3<f32>,
    @location(2) doppler: f32,
    @location(3) intensity: f32,
};

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    out.clip = camera.view_proj * vec4<f32>(v.position, 1.0);
    out.position = v.position;
    out.colour = v.colour;
    out.doppler = v.doppler;
    out.intensity = v.intensity;
    return out;
}

// The emitted spectrum implied by an RGB colour: piecewise linear through
// the channels at 465 (B), 550 (G) and 610 nm (R), fading to 0 at 380 and
// 720 nm.
fn spectrum(c: vec3<f32>, lambda: f32) -> f32 {
    if (lambda <= 380.0 || lambda >= 720.0) { return 0.0; }
    if (lambda < 465.0) { return c.b * (lambda - 380.0) / 85.0; }
    if (lambda < 550.0) { return mix(c.b, c.g, (lambda - 465.0) / 85.0); }
    if (lambda < 610.0) { return mix(c.g, c.r, (lambda - 550.0) / 60.0); }
    return c.r * (720.0 - lambda) / 110.0;
}

// Doppler shift: light observed at wavelength λ left the source at λ·D.
fn shift(c: vec3<f32>, d: f32) -> vec3<f32> {
    if (abs(d - 1.0) < 1e-6) { return c; }
    return vec3<f32>(spectrum(c, 610.0 * d), spectrum(c, 550.0 * d), spectrum(c, 465.0 * d));
}

fn luminance(c: vec3<f32>) -> f32 {
    return dot(c, vec3<f32>(0.2126, 0.7152, 0.0722));
}

// The Doppler-shifted hue at the colour's own luminance: the shift moves
// the spectrum (the hue turns bluer approaching, redder receding) without
// turning a puck black or blinding white, so every puck stays visible;
// brightness is the searchlight's effect, applied separately. A spectrum
// shifted wholly out of the visible band shows as deep violet (D > 1) or
// deep red (D < 1).
fn shift_hue(c: vec3<f32>, d: f32) -> vec3<f32> {
    if (abs(d - 1.0) < 1e-6) { return c; }
    let y0 = luminance(c);
    var s = shift(c, d);
    if (luminance(s) < 1e-4) {
        s = select(vec3<f32>(1.0, 0.05, 0.0), vec3<f32>(0.35, 0.1, 1.0), d > 1.0);
    }
    return s * (y0 / luminance(s));
}

// The fragment's linear colour.
fn shade(f: VertexOut) -> vec3<f32> {
    let n = normalize(cross(dpdx(f.position), dpdy(f.position)));
    let facing = abs(dot(n, normalize(camera.light.xyz)));
    let lit = 0.35 + 0.65 * facing;
    let c = shift_hue(f.colour, f.doppler) * f.intensity * lit;
    return min(c, vec3<f32>(1.0));
}

// Into an sRGB target (which encodes what it stores).
@fragment
fn fs_main(f: VertexOut) -> @location(0) vec4<f32> {
    return vec4<f32>(shade(f), 1.0);
}

// sRGB's encoding (IEC 61966-2-1), for a target that stores the value as
// given.
fn encode_srgb(c: vec3<f32>) -> vec3<f32> {
    let low = c * 12.92;
    let high = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(high, low, c <= vec3<f32>(0.0031308));
}

// Into a target that stores the value as given (a browser's canvas drawn
// without wgpu's sRGB presentation pass: the window's format, chosen in
// game/src/play/window.rs).
@fragment
fn fs_main_encoded(f: VertexOut) -> @location(0) vec4<f32> {
    return vec4<f32>(encode_srgb(shade(f)), 1.0);
}
