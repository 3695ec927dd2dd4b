# nginx from Debian 12, with deploy/nginx.conf.
FROM debian:12
RUN apt-get update -qq && apt-get install -y -qq --no-install-recommends nginx \
    && rm -rf /var/lib/apt/lists/*
COPY nginx.conf /etc/nginx/seaplan.conf
EXPOSE 50051 8080
CMD ["nginx", "-c", "/etc/nginx/seaplan.conf", "-g", "daemon off;"]
