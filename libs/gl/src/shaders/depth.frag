#version 450 core
// Depth is written by the fixed-function stage; polygon offset supplies the bias.
void main() {}
