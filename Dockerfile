# seaplan server image: a thin wrapper over the tested scripts.
#   DOCKER_BUILDKIT=1 docker build -t seaplan .
#   docker run -p 50051:50051 -p 8443:8080 -v seaplan-data:/data -v /etc/seaplan/tls:/tls:ro seaplan
# BuildKit (the default builder since Docker 23; DOCKER_BUILDKIT=1 with
# Debian 12's docker.io 20.10) keeps the compiler cache (ccache), npm's
# download cache and apt's downloads between builds in cache mounts: a
# rebuild after a small change recompiles only what changed, and none of
# those caches ends up in a layer. The legacy builder refuses `RUN --mount`.
# The server listens on all interfaces inside the container, so it serves
# only with TLS: /tls must hold server.pem (certificate chain) and server.key
# (server/README.md shows how to make them). A trial on a trusted host
# without certificates: add -e SEAPLAN_INSECURE=1 -e SEAPLAN_TLS_CERT= -e SEAPLAN_TLS_KEY=
# (plaintext; the server logs a warning).
FROM debian:12 AS build
WORKDIR /src
COPY scripts/install-deps.sh scripts/install-deps.sh
RUN --mount=type=cache,target=/var/cache/apt,sharing=locked \
    --mount=type=cache,target=/var/lib/apt/lists,sharing=locked \
    bash scripts/install-deps.sh && apt-get install -y -qq --no-install-recommends ccache
COPY . .
ENV CCACHE_DIR=/root/.ccache
# npm fetches the console's packages over HTTPS. Behind a proxy that re-signs
# TLS, give its CA certificate as a build secret (not stored in the image):
#   docker build --secret id=ca,src=proxy-ca.pem ...
RUN --mount=type=cache,target=/root/.ccache \
    --mount=type=cache,target=/root/.npm \
    --mount=type=secret,id=ca \
    if [ -f /run/secrets/ca ]; then export NODE_EXTRA_CA_CERTS=/run/secrets/ca; fi; \
    CMAKE_ARGS="-DSEAPLAN_BUILD_TESTS=OFF -DSEAPLAN_BUILD_BENCH=OFF \
      -DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache" \
    BUILD_TYPE=Release bash scripts/build.sh && ccache --show-stats

FROM debian:12 AS runtime
COPY scripts/install-deps.sh /tmp/install-deps.sh
RUN --mount=type=cache,target=/var/cache/apt,sharing=locked \
    --mount=type=cache,target=/var/lib/apt/lists,sharing=locked \
    bash /tmp/install-deps.sh --runtime && rm /tmp/install-deps.sh
COPY --from=build /src/build/bin/seaplan-server /src/build/bin/seaplan /src/build/bin/seaplan-remote /src/build/bin/seaplan-charts /src/build/bin/seaplan-sim /usr/local/bin/
# The operator console, beside the server (its default --console-dir).
COPY --from=build /src/build/bin/console /usr/local/bin/console
COPY --from=build /src/examples /usr/share/seaplan/examples
VOLUME /data /tls
EXPOSE 50051 8080
# Listen on all interfaces inside the container; the host decides what to publish.
ENV SEAPLAN_GRPC_ADDR=0.0.0.0:50051 SEAPLAN_HTTP_ADDR=0.0.0.0:8080 SEAPLAN_DATA_DIR=/data \
    SEAPLAN_TLS_CERT=/tls/server.pem SEAPLAN_TLS_KEY=/tls/server.key
ENTRYPOINT ["/usr/local/bin/seaplan-server"]
