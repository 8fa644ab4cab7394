uniform vec4 uColor;

out vec4 outColor;

void main() { outColor = uColor; }
