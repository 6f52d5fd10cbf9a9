// railwear command-line entry point. Exit codes: 0 ok, 1 runtime or numerical failure,
// 2 bad input or usage.
int main() { return 0; }
