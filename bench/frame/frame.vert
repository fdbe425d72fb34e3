/* frame.vert - the full-screen triangle of bench/frame (no vertex buffer: three vertices from
   gl_VertexIndex, covering the viewport; the fragment shader does the rest). */
#version 450
void main()
{
    vec2 p = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));
    gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
