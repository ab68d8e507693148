#pragma once
// Typed publish/subscribe between modules (DESIGN.md §3): a module publishes a message of type M,
// every subscriber of M receives it synchronously, in subscription order. Observations from the
// rawlog are routed by sensor label.
#include <mrpt/obs/CObservation.h>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <typeindex>
#include <vector>

namespace rpvio {

class RawlogReader;

/// An observation as the rawlog player hands it out; `reader` resolves lazy-loaded images and
/// names the rawlog position in error messages.
struct ObservationMessage {
  mrpt::obs::CObservation::Ptr observation;
  const RawlogReader* reader = nullptr;
};

class Bus {
 public:
  /// A subscriber of a message published with publishRetained() gets the last one at once.
  template <typename Message>
  void subscribe(std::function<void(const Message&)> handler) {
    const std::type_index type(typeid(Message));
    handlers_[type].push_back(
        [h = std::move(handler)](const void* m) { h(*static_cast<const Message*>(m)); });
    if (const auto kept = retained_.find(type); kept != retained_.end())
      handlers_[type].back()(kept->second.get());
  }
  /// Publishes and keeps the message for the modules that subscribe later (a module's state that
  /// the modules listed after it need too, e.g. MapReady).
  template <typename Message>
  void publishRetained(const Message& message) {
    retained_[std::type_index(typeid(Message))] = std::make_shared<Message>(message);
    publish(message);
  }
  template <typename Message>
  void publish(const Message& message) const {
    const auto it = handlers_.find(std::type_index(typeid(Message)));
    if (it == handlers_.end()) return;
    for (const auto& h : it->second) h(&message);
  }
  void subscribeSensor(const std::string& label,
                       std::function<void(const ObservationMessage&)> handler) {
    sensor_handlers_[label].push_back(std::move(handler));
  }
  void publishObservation(const ObservationMessage& message) const {
    const auto it = sensor_handlers_.find(message.observation->sensorLabel);
    if (it == sensor_handlers_.end()) return;
    for (const auto& h : it->second) h(message);
  }
  bool hasSensorSubscribers(const std::string& label) const {
    return sensor_handlers_.count(label) > 0;
  }

 private:
  std::map<std::type_index, std::vector<std::function<void(const void*)>>> handlers_;
  std::map<std::type_index, std::shared_ptr<const void>> retained_;
  std::map<std::string, std::vector<std::function<void(const ObservationMessage&)>>>
      sensor_handlers_;
};

}  // namespace rpvio
