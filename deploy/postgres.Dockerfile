# PostgreSQL 15 from Debian 12, for compose.yaml: built from debian:12 like
# the other images, so nothing but debian:12 and Debian's mirror is needed.
# First start: a cluster in $PGDATA whose superuser is $POSTGRES_USER with
# $POSTGRES_PASSWORD, and the database $POSTGRES_DB (postgres-init.sh).
FROM debian:12
RUN apt-get update -qq && apt-get install -y -qq --no-install-recommends postgresql-15 \
    && pg_dropcluster 15 main \
    && rm -rf /var/lib/apt/lists/* \
    && install -d -o postgres -g postgres -m 700 /var/lib/postgresql/data
COPY postgres-init.sh /usr/local/bin/postgres-init.sh
ENV PATH=/usr/lib/postgresql/15/bin:$PATH PGDATA=/var/lib/postgresql/data
VOLUME /var/lib/postgresql/data
USER postgres
EXPOSE 5432
STOPSIGNAL SIGINT
ENTRYPOINT ["bash", "/usr/local/bin/postgres-init.sh"]
