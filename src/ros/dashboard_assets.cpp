// Dashboard's page, style and scripts (ES modules), compiled into the binary from
// src/ros/dashboard_web/ (the build wraps each in a raw string literal: cmake/embed_asset.cmake), so
// the node needs no files and no network to serve them. A new module: here and in cmake/monitor.cmake.
#include "rocking_monitor/ros/dashboard.hpp"

#include <iterator>

namespace rocking_monitor::live {

namespace {

constexpr const char* kHtml = "text/html; charset=utf-8";
constexpr const char* kCss = "text/css; charset=utf-8";
constexpr const char* kJs = "application/javascript; charset=utf-8";

}  // namespace

// index.html first: it is also the page at "/".
const Dashboard::WebAsset Dashboard::kWebAssets[] = {
    {"/index.html", kHtml,
#include "dashboard_web/index.html.inc"
    },
    {"/style.css", kCss,
#include "dashboard_web/style.css.inc"
    },
    {"/app.js", kJs,
#include "dashboard_web/app.js.inc"
    },
    {"/state.js", kJs,
#include "dashboard_web/state.js.inc"
    },
    {"/plan.js", kJs,
#include "dashboard_web/plan.js.inc"
    },
    {"/item_view.js", kJs,
#include "dashboard_web/item_view.js.inc"
    },
    {"/alarms.js", kJs,
#include "dashboard_web/alarms.js.inc"
    },
    {"/health.js", kJs,
#include "dashboard_web/health.js.inc"
    },
};
const std::size_t Dashboard::kWebAssetCount = std::size(kWebAssets);

}  // namespace rocking_monitor::live
