// Connects to mmh-viewer with the Foxglove WebSocket protocol's own client (@foxglove/ws-protocol)
// and checks what a Foxglove or Lichtblick user gets: the channels advertised with JSON schemas,
// and odometry and trajectory messages that carry every property their schema requires.
//   node --experimental-websocket foxglove_client_check.mjs ws://127.0.0.1:8765/ TIMEOUT_S
import foxglove from "@foxglove/ws-protocol";

const { FoxgloveClient } = foxglove;
const [url, timeoutText = "30"] = process.argv.slice(2);
const wanted = { "/mmh/odometry": 20, "/mmh/trajectory": 1 };
const received = {};
const requiredOf = new Map();
const topicOfSubscription = new Map();
let channelsSeen = [];

function finish(code, text) {
  console.log(`${code === 0 ? "ok" : "FAIL"}: ${text}`);
  console.log(`foxglove: channels ${channelsSeen.length}; received ${JSON.stringify(received)}`);
  process.exit(code);
}
setTimeout(() => finish(1, `timeout after ${timeoutText} s`), Number(timeoutText) * 1000);

const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
client.on("error", (e) => finish(1, `socket error ${e?.message ?? e}`));
client.on("advertise", (channels) => {
  channelsSeen = channels;
  for (const c of channels) {
    if (c.encoding !== "json" || c.schemaEncoding !== "jsonschema") finish(1, `${c.topic}: not a JSON channel`);
    const schema = JSON.parse(c.schema);
    if (schema.type !== "object" || !Array.isArray(schema.required)) finish(1, `${c.topic}: schema is not an object schema`);
    requiredOf.set(c.topic, schema.required);
  }
  for (const topic of Object.keys(wanted)) {
    const channel = channels.find((c) => c.topic === topic);
    if (!channel) finish(1, `no channel ${topic}`);
    topicOfSubscription.set(client.subscribe(channel.id), topic);
  }
});
const decoder = new TextDecoder();
client.on("message", ({ subscriptionId, data }) => {
  const topic = topicOfSubscription.get(subscriptionId);
  const message = JSON.parse(decoder.decode(data));
  const missing = requiredOf.get(topic).filter((key) => !(key in message));
  if (missing.length) finish(1, `${topic} message lacks ${missing.join(", ")}`);
  if (topic === "/mmh/odometry" && message.position.length !== 3) finish(1, "odometry position is not 3D");
  if (topic === "/mmh/trajectory" && message.points.length < 6) finish(1, "trajectory has no points");
  received[topic] = (received[topic] ?? 0) + 1;
  if (Object.entries(wanted).every(([t, n]) => (received[t] ?? 0) >= n)) finish(0, "odometry and trajectory received");
});
