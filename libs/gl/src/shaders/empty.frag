// Depth only (occlusion queries count the samples that pass the depth test).
void main() {}
