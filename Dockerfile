# The `eulerdisk` command in a small image, for sweeps on a cluster (docs/k8s-sweep-job.yaml).
#
#   docker build -t eulerdisk:latest .
#   docker run --rm -v "$PWD/out:/out" eulerdisk:latest run tangent-toy -o /out -q
#   docker run --rm -v "$PWD/out:/out" eulerdisk:latest sweep paper-friction -o /out/sweep
#
# Two stages: the first compiles with the full Rust toolchain, the second holds only the
# binary, stripped, on a slim Debian (the program needs nothing but the C library). Built
# without the git history (.dockerignore), a run's `summary.json` names the revision
# `unknown (built without git)`. No CI step needs Docker; CI checks the Kubernetes files.

FROM rust:1.88-slim-bookworm AS build
WORKDIR /src
COPY . .
RUN CARGO_PROFILE_RELEASE_STRIP=true cargo build --release --locked --bin eulerdisk

FROM debian:bookworm-slim
COPY --from=build /src/target/release/eulerdisk /usr/local/bin/eulerdisk
RUN useradd --create-home --uid 1000 eulerdisk
USER eulerdisk
WORKDIR /home/eulerdisk
ENTRYPOINT ["eulerdisk"]
CMD ["--help"]
