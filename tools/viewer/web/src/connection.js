// The page's link to mmh-viewer: a Foxglove WebSocket client (the same protocol Foxglove and
// Lichtblick speak) that subscribes to every advertised channel and hands each decoded JSON
// message to onMessage(topic, payload). Reconnects a second after the socket closes.
import { FoxgloveClient } from "@foxglove/ws-protocol";

export function connect(url, { onMessage, onStatus }) {
  const decoder = new TextDecoder();
  let attempt = 0;
  const open = () => {
    attempt += 1;
    const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
    const topicOfSubscription = new Map();
    client.on("open", () => onStatus("connected", attempt));
    client.on("advertise", (channels) => {
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
      onStatus("disconnected", attempt);
      setTimeout(open, 1000);
    });
    client.on("error", () => {});
  };
  open();
}
