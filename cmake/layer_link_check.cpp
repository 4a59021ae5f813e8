// Entry point of the layer link checks (cmake/layers.cmake): the program only has to link, it is
// never run.
int main() { return 0; }
