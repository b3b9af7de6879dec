// The JSON API of pkm serve (docs/web.md): every request the page makes goes through here.

/** An API error: the server's message, and the program or file name and line when it gave them. */
export class ApiError extends Error {
  constructor(status, body) {
    super(body.error || `HTTP ${status}`);
    this.status = status;
    this.name_ = body.name;
    this.line = body.line;
  }
}

async function parse(response) {
  const body = await response.json().catch(() => ({ error: `HTTP ${response.status}` }));
  if (!response.ok) throw new ApiError(response.status, body);
  return body;
}

export const get = async (path) => parse(await fetch(path));

export const post = async (path, body, signal) =>
  parse(
    await fetch(path, {
      method: "POST",
      headers: { "Content-Type": "application/json" },
      body: JSON.stringify(body),
      signal,
    }),
  );

/**
 * POSTs `body` to `path` and reads the server-sent events of the answer as they come, calling
 * onEvent(name, data) for each. Resolves when the stream ends; `signal` (an AbortSignal) closes it.
 */
export async function streamEvents(path, body, onEvent, signal) {
  const response = await fetch(path, {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify(body),
    signal,
  });
  if (!response.ok) await parse(response);
  const reader = response.body.getReader();
  const decoder = new TextDecoder();
  let buffer = "";
  for (;;) {
    const { value, done } = await reader.read();
    if (done) break;
    buffer += decoder.decode(value, { stream: true });
    let end;
    while ((end = buffer.indexOf("\n\n")) >= 0) {
      const block = buffer.slice(0, end);
      buffer = buffer.slice(end + 2);
      const name = /^event: (.*)$/m.exec(block)?.[1];
      const data = /^data: (.*)$/m.exec(block)?.[1];
      if (name && data) onEvent(name, JSON.parse(data));
    }
  }
}

/** POST /api/campaign: the campaign's events as they come (streamEvents). */
export const streamCampaign = (campaign, onEvent) => streamEvents("/api/campaign", { campaign }, onEvent);
