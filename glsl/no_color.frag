#version 450 core
// For passes that only touch depth and stencil.
void main() {}
