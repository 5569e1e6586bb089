# Case registration is filled in by the framework (see benchmarks/README.md).
