namespace cutbench::framework {
int placeholder() { return 0; }
}
