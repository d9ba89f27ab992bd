// The page's link to mmh-viewer: a Foxglove WebSocket client (the same protocol Foxglove and
// Lichtblick speak) that subscribes to every advertised channel and hands each decoded JSON
// message to onMessage(topic, payload); onChannels(topics) tells which channels the server has.
// Reconnects a second after the socket closes. Returns { setParameters } (mmh-viewer --log's
// playback.* parameters).
import { FoxgloveClient } from "@foxglove/ws-protocol";

export function connect(url, { onMessage, onStatus, onChannels = () => {} }) {
  const decoder = new TextDecoder();
  let attempt = 0;
  let current = null;
  const open = () => {
    attempt += 1;
    const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
    current = client;
    const topicOfSubscription = new Map();
    client.on("open", () => onStatus("connected", attempt));
    client.on("advertise", (channels) => {
      onChannels(channels.map((c) => c.topic));
      for (const channel of channels) {
        const id = client.subscribe(channel.id);
        topicOfSubscription.set(id, channel.topic);
      }
    });
    client.on("message", ({ subscriptionId, data }) => {
      const topic = topicOfSubscription.get(subscriptionId);
      if (topic === undefined) return;
      onMessage(topic, JSON.parse(decoder.decode(data)));
    });
    client.on("close", () => {
      current = null;
      onStatus("disconnected", attempt);
      setTimeout(open, 1000);
    });
    client.on("error", () => {});
  };
  open();
  return {
    setParameters: (parameters) => current?.setParameters(parameters),
  };
}
