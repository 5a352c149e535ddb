// Dashboard's page, script and style, compiled into the binary from src/ros/dashboard_web/ (the build
// wraps each in a raw string literal: cmake/embed_asset.cmake), so the node needs no files and no
// network to serve them.
#include "rocking_monitor/ros/dashboard.hpp"

namespace rocking_monitor::live {

const char* const Dashboard::kIndexHtml =
#include "dashboard_web/index.html.inc"
    ;
const char* const Dashboard::kAppJs =
#include "dashboard_web/app.js.inc"
    ;
const char* const Dashboard::kStyleCss =
#include "dashboard_web/style.css.inc"
    ;

}  // namespace rocking_monitor::live
