#include "rocking_monitor/ros/catalogue.hpp"

#include <nlohmann/json.hpp>

namespace rocking_monitor::live {

nlohmann::json to_json(const XmlRpc::XmlRpcValue& value) {
  auto& v = const_cast<XmlRpc::XmlRpcValue&>(value);  // XmlRpcValue's accessors are not const
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean: return static_cast<bool>(v);
    case XmlRpc::XmlRpcValue::TypeInt: return static_cast<int>(v);
    case XmlRpc::XmlRpcValue::TypeDouble: return static_cast<double>(v);
    case XmlRpc::XmlRpcValue::TypeString: return static_cast<std::string>(v);
    case XmlRpc::XmlRpcValue::TypeArray: {
      nlohmann::json a = nlohmann::json::array();
      for (int i = 0; i < v.size(); ++i) a.push_back(to_json(v[i]));
      return a;
    }
    case XmlRpc::XmlRpcValue::TypeStruct: {
      nlohmann::json o = nlohmann::json::object();
      for (auto it = v.begin(); it != v.end(); ++it) o[it->first] = to_json(it->second);
      return o;
    }
    default: return nullptr;
  }
}

Catalogue parse_catalogue(const XmlRpc::XmlRpcValue& sensors, const XmlRpc::XmlRpcValue& items) {
  return core::parse_catalogue(to_json(sensors), to_json(items));
}

}  // namespace rocking_monitor::live
