// One "vertex" per patch: the patch index travels to the tessellator, which reads the patch's
// control points from SSBOs. (Indexing by gl_VertexID also sidesteps llvmpipe's gl_PrimitiveID
// restarting every 1024 indices in tessellation stages.)
flat out int vPatch;

void main() { vPatch = gl_VertexID; }
