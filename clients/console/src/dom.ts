// Small DOM helpers (no framework: the console is a handful of views).
export function h<K extends keyof HTMLElementTagNameMap>(
    tag: K, attrs: Record<string, string | number | boolean | undefined> = {},
    ...children: (Node | string | null | undefined)[]): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === undefined || v === false) continue;
    if (k === "class") e.className = String(v);
    else if (k === "text") e.textContent = String(v);
    else e.setAttribute(k, v === true ? "" : String(v));
  }
  for (const c of children) if (c !== null && c !== undefined) e.append(c);
  return e;
}

// A labelled form field: <label for=id>text</label> + control.
export function field(label: string, control: HTMLElement, hint?: string): HTMLElement {
  const id = control.id || `f-${Math.random().toString(36).slice(2, 9)}`;
  control.id = id;
  return h("div", { class: "field" }, h("label", { for: id, text: label }), control,
           hint ? h("small", { class: "hint", text: hint }) : null);
}

export function readFileText(input: HTMLInputElement): Promise<string | undefined> {
  const f = input.files?.[0];
  return f ? f.text() : Promise.resolve(undefined);
}

export function fileToBase64(file: File): Promise<string> {
  return new Promise((resolve, reject) => {
    const r = new FileReader();
    r.onerror = () => reject(r.error);
    r.onload = () => resolve(String(r.result).replace(/^data:[^,]*,/, ""));
    r.readAsDataURL(file);
  });
}
